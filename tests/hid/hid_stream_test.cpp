// Host-planned motion over USB HID (the fake board, simulated time): the stream's floor is
// the board forwarding six servo commands on its servo bus, one point arrives per period and
// the arm ends where the plan does.
#include <gtest/gtest.h>

#include <cmath>

#include "arm/arm.hpp"
#include "arm/motion_executor.hpp"
#include "arm/motion_planning.hpp"
#include "arm/rc_arm_device.hpp"
#include "devices/robot_commands/client.hpp"
#include "devices/robot_commands/hid_link.hpp"
#include "fake_hid_backend.hpp"

namespace armctl::robot_commands {
namespace {

TEST(HidStream, PeriodIsTheBoardsServoBusTimeAndTheMotionArrives) {
  armctl::testing::FakeHidBackend fake{armctl::testing::FakeHidBehaviour{}};
  auto link = HidLink::open_board("", fake);
  // One 64-byte report per 1 ms USB frame, then 6 x 10 bytes at 115200 on the servo bus.
  EXPECT_EQ(link->frame_time(25), wire_time(60, 115200));
  Client client(*link, hid_client_options());
  const arm::ArmModel model = arm::load_arm_model(arm::arm_file_path("xarm")).value();
  arm::Arm a(model, std::make_unique<arm::RcArmDevice>(model, client));
  EXPECT_EQ(a.device().stream_period(false), wire_time(60, 115200));
  const auto from = a.read().value().positions;
  arm::JointMove move;
  move.target = from;
  move.target[0] += 0.5;  // rad, servo6
  auto plan = arm::plan_joint_move(model, from, move);
  ASSERT_TRUE(plan) << plan.error().message;
  auto r = arm::execute_motion(a, *plan);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
  // One point per 5.2 ms period while it moves (reads every 500 ms on HID take a few).
  EXPECT_GT(double(r->points), 0.8 * plan->duration / 0.0052);
  auto end = a.wait();
  ASSERT_TRUE(end) << end.error().message;
  EXPECT_NEAR(end->positions[0], move.target[0], 0.005);
}

}  // namespace
}  // namespace armctl::robot_commands

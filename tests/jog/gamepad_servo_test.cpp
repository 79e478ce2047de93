// Recorded gamepad streams driving both simulated arms through the servo mode, on simulated
// time, through the same feed as `armctl jog --gamepad-replay` (jog/gamepad_feed.hpp): the
// tool moves the way the stick is pushed, and stops when the dead-man is let go and when
// the pad is unplugged, though the stick stays pushed.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm/run_servo.hpp"
#include "arm/arm_files.hpp"
#include "jog/gamepad_feed.hpp"
#include "jog/gamepad_replay.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::jog {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// Where the tool was (mm) at each time (s from the start), and the lines said.
struct ToolTrace {
  std::vector<std::pair<double, Eigen::Vector3d>> points;
  std::vector<std::string> lines;
  // The tool's place at `t` s (the first point at or after it).
  Eigen::Vector3d at(double t) const {
    for (const auto& [time, p] : points)
      if (time >= t) return p;
    return points.back().second;
  }
};

ToolTrace replay(arm::Arm& arm, const PadRecording& recording) {
  GamepadReplay source(recording, "test");
  GamepadJog pad(arm.model());
  arm::ServoInput input(arm.model());
  ToolTrace trace;
  arm::ServoOptions o;
  o.before_cycle = [&](TimePoint now) {
    for (auto& line : feed_gamepad(source, pad, input, now)) trace.lines.push_back(line);
  };
  o.on_cycle = [&](const arm::ServoStatus& s) {
    trace.points.emplace_back(std::chrono::duration<double>(s.elapsed).count(),
                              arm.kinematics()->pose_at(s.positions).position * 1000);
  };
  auto r = arm::run_servo(arm, input, o);
  EXPECT_TRUE(r) << r.error().message;
  return trace;
}

TEST(GamepadOnTheXarm, TheRecordedStickMovesTheToolForwardAndItStopsOnReleaseAndUnplug) {
  robot_commands::testing::EmulatedLink link{115200};
  robot_commands::Client client{link};
  arm::Arm arm{arm::testing::shipped("xarm"),
               std::make_unique<arm::RcArmDevice>(arm::testing::shipped("xarm"), client)};
  // Away from the upright start (a singularity) first.
  ASSERT_TRUE(arm.move_joints({0.0, 30 * kDeg, 60 * kDeg, 60 * kDeg, 0.0, std::nullopt}));
  ASSERT_TRUE(arm.wait());
  auto rec = read_pad_recording(ARMCTL_SOURCE_DIR "/tests/jog/recordings/xbox_forward.txt");
  ASSERT_TRUE(rec) << rec.error().message;
  const ToolTrace t = replay(arm, *rec);

  // Held: 0.1 s at 43 % of 25 mm/s, then 1 s at 25 mm/s; the start and the stop's ramps
  // about cancel.
  const Eigen::Vector3d first = t.at(1.9) - t.at(0);
  EXPECT_NEAR(first.x(), 26, 1.5);
  EXPECT_LT(std::abs(first.y()), 1.0);
  EXPECT_LT(std::abs(first.z()), 1.0);
  // LB let go at 1.2 s with the stick still forward: at rest well before LB comes back at 2.
  EXPECT_LT((t.at(1.95) - t.at(1.6)).norm(), 0.05);
  // Pressed again: a second at 25 mm/s until the pad is unplugged at 3 s.
  EXPECT_NEAR((t.at(3.9) - t.at(1.95)).x(), 25, 1.5);
  // Unplugged with LB and the stick still held: stopped, and plugged in again (the stick
  // then centred) it stays.
  EXPECT_LT((t.points.back().second - t.at(3.5)).norm(), 0.05);
  EXPECT_EQ(t.lines.front(), "gamepad 'Microsoft X-Box 360 pad' (Xbox layout): hold LB to move");
  EXPECT_NE(std::find(t.lines.begin(), t.lines.end(), "gamepad lost: stopping; waiting for a gamepad"), t.lines.end());
}

// A PlayStation pad (hid-playstation: sticks 0..255) on the simulated SCARA: the left stick
// pushed left (y+) and R2 (z up) held, then L1 let go.
TEST(GamepadOnTheScara, TheLeftStickAndR2MoveTheToolLeftAndUpAndL1sReleaseStopsIt) {
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm(115200);
  joint_bus::BusMaster master{sim->link()};
  arm::Arm arm{arm::testing::shipped("scara"),
               std::make_unique<arm::BusArmDevice>(arm::testing::shipped("scara"), master, sim->link(),
                                                   "simulated SCARA")};
  // The simulated arm starts stretched out (a singularity): a bent elbow and Z mid-travel first.
  std::vector<std::optional<double>> bent(std::size_t(arm.model().joint_count()));
  bent[0] = 0.15;
  bent[2] = 60 * kDeg;
  ASSERT_TRUE(arm.move_joints(bent));
  ASSERT_TRUE(arm.wait());

  auto rec = parse_pad_recording(
      "device Sony Interactive Entertainment DualSense Wireless Controller\n"
      "axis ABS_X 0 255\naxis ABS_Y 0 255\naxis ABS_RX 0 255\naxis ABS_RY 0 255\n"
      "axis ABS_Z 0 255\naxis ABS_RZ 0 255\n"
      "0.0 EV_KEY BTN_TL 1\n0.0 EV_SYN SYN_REPORT 0\n"
      "0.0 EV_ABS ABS_X 0\n0.0 EV_ABS ABS_RZ 255\n0.0 EV_SYN SYN_REPORT 0\n"
      "1.0 EV_KEY BTN_TL 0\n1.0 EV_SYN SYN_REPORT 0\n"
      "2.0 EV_SYN SYN_REPORT 0\n",
      "dualsense");
  ASSERT_TRUE(rec) << rec.error().message;
  const ToolTrace t = replay(arm, *rec);
  const Eigen::Vector3d moved = t.at(1.5) - t.at(0);
  EXPECT_NEAR(moved.y(), 25, 1.5);
  EXPECT_NEAR(moved.z(), 25, 1.5);
  EXPECT_LT(std::abs(moved.x()), 1.0);
  EXPECT_LT((t.points.back().second - t.at(1.5)).norm(), 0.05);
  EXPECT_EQ(t.lines.front(),
            "gamepad 'Sony Interactive Entertainment DualSense Wireless Controller' (PlayStation layout): hold L1 "
            "to move");
}

}  // namespace
}  // namespace armctl::jog

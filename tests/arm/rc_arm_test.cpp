// The Arm API over Robot Commands: the emulated xArm in process, on simulated time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "arm/arm.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm_files.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

class RcArm : public ::testing::Test {
 protected:
  robot_commands::testing::EmulatedLink link;
  robot_commands::Client client{link};
  Arm arm{testing::shipped("xarm"), std::make_unique<RcArmDevice>(testing::shipped("xarm"), client)};

  std::vector<std::optional<double>> none() const { return std::vector<std::optional<double>>(6); }
  double seconds() const { return std::chrono::duration<double>(link.clock().now().time_since_epoch()).count(); }
};

TEST_F(RcArm, StartsAtCentreWhichIsZero) {
  auto s = arm.read();
  ASSERT_TRUE(s) << s.error().message;
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_NEAR(s->device[i], 500, 0.5);
    EXPECT_NEAR(s->positions[i], 0, 1e-9);
  }
}

TEST_F(RcArm, MoveJointsArrivesInTheTimeAsked) {
  auto t = none();
  t[1] = 30 * kDeg;   // servo5
  t[2] = -45 * kDeg;  // servo4
  MoveOptions o;
  o.duration = std::chrono::milliseconds(1500);
  const double t0 = seconds();
  ASSERT_TRUE(arm.move_joints(t, o));
  auto s = arm.wait();
  ASSERT_TRUE(s) << s.error().message;
  const double took = seconds() - t0;
  EXPECT_GE(took, 1.45);
  EXPECT_LE(took, 1.5 + 2 * 0.2 + 0.05);  // arrival seen within two polls (200 ms on serial)
  EXPECT_NEAR(s->positions[1], 30 * kDeg, 0.5 * kDeg);  // the wait's tolerance
  EXPECT_NEAR(s->positions[2], -45 * kDeg, 0.5 * kDeg);
  EXPECT_NEAR(s->positions[0], 0, 1e-9);  // untouched
}

TEST_F(RcArm, MoveToReachesThePoseWithinServoResolution) {
  motion::JointVector q(5);
  q << 20 * kDeg, 25 * kDeg, 40 * kDeg, 30 * kDeg, 10 * kDeg;
  const motion::Pose want = arm.forward(q);
  const motion::Rpy rpy = motion::to_rpy(want.orientation);
  CartesianGoal g;
  g.position = want.position;
  g.pitch = rpy.pitch;
  g.roll = rpy.roll;
  ASSERT_TRUE(arm.move_to(g)) << arm.move_to(g).error().message;
  ASSERT_TRUE(arm.wait());
  auto p = arm.pose();
  ASSERT_TRUE(p);
  // 0.24 deg per servo unit over a reach of about 0.3 m: a few mm at most.
  EXPECT_LT((p->position - want.position).norm(), 0.003);
}

TEST_F(RcArm, RefusedCommandsSendNothing) {
  const std::size_t before = link.sent.size();
  auto t = none();
  t[0] = 130 * kDeg;
  auto r = arm.move_joints(t);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("outside its limits"), std::string::npos) << r.error().message;
  t[0] = std::nan("");
  EXPECT_FALSE(arm.move_joints(t));
  MoveOptions slow;
  slow.speed = 0;
  t[0] = 10 * kDeg;
  EXPECT_FALSE(arm.move_joints(t, slow));
  EXPECT_FALSE(arm.gripper(1.5));
  CartesianGoal far;
  far.position = {1.0, 0, 0.1};
  auto unreachable = arm.move_to(far);
  ASSERT_FALSE(unreachable);
  EXPECT_NE(unreachable.error().message.find("reach"), std::string::npos) << unreachable.error().message;
  // Reads happen (the IK starts from where the arm stands), moves never.
  for (std::size_t i = before; i < link.sent.size(); ++i) EXPECT_NE(link.sent[i].cmd, 3) << "a move was sent";
}

TEST_F(RcArm, WaitNamesTheJointsThatDidNotArrive) {
  auto t = none();
  t[0] = 100 * kDeg;
  MoveOptions o;
  o.duration = std::chrono::milliseconds(2000);
  ASSERT_TRUE(arm.move_joints(t, o));
  WaitOptions w;
  w.timeout = std::chrono::milliseconds(300);
  auto s = arm.wait(w);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::timeout);
  EXPECT_NE(s.error().message.find("servo6 at"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("target 100.000 deg"), std::string::npos) << s.error().message;
}

TEST_F(RcArm, TorqueOffAndGripper) {
  ASSERT_TRUE(arm.set_torque(false));
  // The off frame(s), MultiServoOff, then the read-back that confirms the board handled
  // them, ServoPositionRead (Client::servos_off, docs/usb-hid.md).
  ASSERT_GE(link.sent.size(), 2u);
  EXPECT_EQ(link.sent[link.sent.size() - 2].cmd, 20);
  EXPECT_EQ(link.sent.back().cmd, 21);
  ASSERT_TRUE(arm.gripper(1.0));
  auto s = arm.wait();
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_NEAR(s->positions[5], 48 * kDeg, 0.5 * kDeg);
}

TEST_F(RcArm, StopHoldsWhereTheServosAre) {
  auto t = none();
  t[0] = 90 * kDeg;
  MoveOptions o;
  o.duration = std::chrono::milliseconds(3000);
  ASSERT_TRUE(arm.move_joints(t, o));
  arm.device().idle(std::chrono::milliseconds(1000));
  ASSERT_TRUE(arm.stop());
  const double at_stop = arm.read()->positions[0];
  arm.device().idle(std::chrono::milliseconds(2000));
  EXPECT_NEAR(arm.read()->positions[0], at_stop, 0.5 * kDeg);
  EXPECT_LT(at_stop, 60 * kDeg);
}

}  // namespace
}  // namespace armctl::arm

// The wizard's per-joint steps: direction from the user's answer, the zero at the joint's
// mark (the xArm servo's own offset when it fits, else the file; the SCARA's home), limits
// from the ends with their margin, the gripper's positions.
#include <gtest/gtest.h>

#include <numbers>

#include "arm_files.hpp"
#include "calibration/joint_steps.hpp"

namespace armctl::calibration {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kMm = 1e-3;
using arm::Protocol;

JointAtMark at_mark(const arm::ArmModel& m, int joint, Protocol p, double device) {
  JointAtMark at;
  at.joint = joint;
  at.device = device;
  at.reading = m.joints[std::size_t(joint)].map(p)->to_actuator(device);
  return at;
}

TEST(Direction, OnlyAJointThatWentTheOtherWayIsFlipped) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  EXPECT_FALSE(direction_from_answer(m, 2, true));
  auto c = direction_from_answer(m, 2, false);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->joint, "servo4");
  EXPECT_TRUE(c->flip);
  EXPECT_EQ(c->zero_shift, 0);
  // The flip checks: the joint's travel, turned about its zero, stays inside the limits.
  CalibrationChanges changes;
  changes.joints.push_back(*c);
  EXPECT_TRUE(check_changes(m, changes));
}

TEST(Zero, AnXarmServoTakesTheOffsetWhenItFits) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  const int elbow = *m.find_joint("servo4");
  JointAtMark at = at_mark(m, elbow, Protocol::robot_commands, 530);  // 7.2 deg past its zero
  at.servo_offsets = true;
  auto step = zero_at_mark(m, Protocol::robot_commands, at);
  ASSERT_TRUE(step) << step.error().message;
  EXPECT_EQ(step->kind, ZeroStep::Kind::servo_offset);
  ASSERT_TRUE(step->servo_offset);
  EXPECT_EQ(step->servo_offset->servo, 4);
  EXPECT_EQ(step->servo_offset->units, 30);
  EXPECT_FALSE(step->change);
  // An offset already held: the reading (in the commanded frame) plus what the servo holds is
  // where its shaft stands, 510; 500 wanted.
  at.servo_offset = -20;
  step = zero_at_mark(m, Protocol::robot_commands, at);
  ASSERT_TRUE(step);
  EXPECT_EQ(step->servo_offset->units, 10);
  EXPECT_NE(step->why.find("shaft stands at 510"), std::string::npos) << step->why;
}

TEST(Zero, BeyondTheServosOffsetRangeTheFileTakesIt) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  const int elbow = *m.find_joint("servo4");
  JointAtMark at = at_mark(m, elbow, Protocol::robot_commands, 700);  // 48 deg: 200 units
  at.servo_offsets = true;
  auto step = zero_at_mark(m, Protocol::robot_commands, at);
  ASSERT_TRUE(step) << step.error().message;
  EXPECT_EQ(step->kind, ZeroStep::Kind::file_zero);
  ASSERT_TRUE(step->change);
  EXPECT_NEAR(step->change->zero_shift, -48 * kDeg, 1e-9);
  EXPECT_NE(step->why.find("-125..125"), std::string::npos) << step->why;
  // The shift makes the mark read zero.
  CalibrationChanges c;
  c.joints.push_back(*step->change);
  auto checked = check_changes(m, c);
  ASSERT_TRUE(checked) << checked.error().message;
  EXPECT_NEAR(checked->joints[0].devices.at("robot_commands").to_actuator(700), 0, 1e-9);
  // Limits carried over: -120..120 shifted by -48 deg, cut at the URDF's -120.
  EXPECT_NEAR(checked->joints[0].limits.lower, -120 * kDeg, 1e-9);
  EXPECT_NEAR(checked->joints[0].limits.upper, 72 * kDeg, 1e-9);
}

TEST(Zero, TheScaraHomesItsJoints) {
  const arm::ArmModel m = arm::testing::shipped("scara");
  const int shoulder = *m.find_joint("SHOULDER");
  auto step = zero_at_mark(m, Protocol::joint_bus, at_mark(m, shoulder, Protocol::joint_bus, 123));
  ASSERT_TRUE(step) << step.error().message;
  EXPECT_EQ(step->kind, ZeroStep::Kind::home);
  EXPECT_FALSE(step->change);  // count 0 reads 0 deg already
  // Z's count 0 reads 150 mm (its map: -15000..15000 clicks = 0..300 mm): a mark at 150 mm
  // needs no change, a mark at 100 mm does.
  const int z = *m.find_joint("Z");
  JointAtMark at = at_mark(m, z, Protocol::joint_bus, 400);
  at.mark = 150 * kMm;
  step = zero_at_mark(m, Protocol::joint_bus, at);
  ASSERT_TRUE(step);
  EXPECT_FALSE(step->change);
  at.mark = 100 * kMm;
  step = zero_at_mark(m, Protocol::joint_bus, at);
  ASSERT_TRUE(step);
  ASSERT_TRUE(step->change);
  EXPECT_NEAR(step->change->zero_shift, -50 * kMm, 1e-12);
  // The coupled wrist: homing both makes both joints read 0.
  step = zero_at_mark(m, Protocol::joint_bus, at_mark(m, *m.find_joint("SKF"), Protocol::joint_bus, -300));
  ASSERT_TRUE(step);
  EXPECT_FALSE(step->change);
}

TEST(Zero, WithoutAnOffsetOrAHomeTheFileTakesIt) {
  const arm::ArmModel m = arm::testing::shipped("scara");
  const int elbow = *m.find_joint("UAE");
  auto step = zero_at_mark(m, Protocol::robot_commands, at_mark(m, elbow, Protocol::robot_commands, 510));
  ASSERT_TRUE(step);
  EXPECT_EQ(step->kind, ZeroStep::Kind::file_zero);
  EXPECT_NEAR(step->change->zero_shift, -m.joints[std::size_t(elbow)].map(Protocol::robot_commands)->to_actuator(510), 1e-12);
}

TEST(Zero, BadInputIsRefused) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  JointAtMark at;
  at.joint = 9;
  EXPECT_FALSE(zero_at_mark(m, Protocol::robot_commands, at));
  at.joint = 1;
  at.device = std::nan("");
  EXPECT_FALSE(zero_at_mark(m, Protocol::robot_commands, at));
  at.device = 500;
  EXPECT_FALSE(zero_at_mark(m, Protocol::joint_bus, at));  // the xArm has no joint-bus map
  at.servo_offsets = true;
  at.servo_offset = 200;
  EXPECT_FALSE(zero_at_mark(m, Protocol::robot_commands, at));
}

TEST(Limits, TheEndsLessTheMargin) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  auto r = limits_from_ends(m, 0, 110 * kDeg, -100 * kDeg);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_NEAR(r->lower, -100 * kDeg + kLimitMarginAngle, 1e-12);
  EXPECT_NEAR(r->upper, 110 * kDeg - kLimitMarginAngle, 1e-12);
  const arm::ArmModel s = arm::testing::shipped("scara");
  auto z = limits_from_ends(s, 0, -5 * kMm, 290 * kMm);
  ASSERT_TRUE(z);
  EXPECT_NEAR(z->lower, -3 * kMm, 1e-12);
  EXPECT_NEAR(z->upper, 288 * kMm, 1e-12);
}

TEST(Limits, EndsThatExcludeTheZeroOrLeaveNoTravelAreRefused) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  auto r = limits_from_ends(m, 0, 10 * kDeg, 90 * kDeg);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("exclude its zero"), std::string::npos) << r.error().message;
  r = limits_from_ends(m, 0, -2 * kDeg, 2 * kDeg);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("no travel"), std::string::npos) << r.error().message;
  // Within the margin of the zero: the zero would fall outside once the margin is taken.
  r = limits_from_ends(m, 0, -1 * kDeg, 90 * kDeg);
  ASSERT_FALSE(r);
  EXPECT_FALSE(limits_from_ends(m, 0, std::nan(""), 1));
}

TEST(Gripper, OpenAndClosedFromReadings) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  auto g = gripper_from_readings(m, -70 * kDeg, 45 * kDeg);
  ASSERT_TRUE(g);
  EXPECT_EQ(g->open, -70 * kDeg);
  EXPECT_EQ(g->closed, 45 * kDeg);
  EXPECT_FALSE(gripper_from_readings(m, 10 * kDeg, 12 * kDeg));
  const arm::ArmModel s = arm::testing::shipped("scara");
  EXPECT_TRUE(gripper_from_readings(s, 1 * kMm, 38 * kMm));
}

}  // namespace
}  // namespace armctl::calibration

// Stall protection on both simulated arms, on simulated time: a joint held by an obstacle the
// host does not know is stopped and its torque released, and the error (device, detail
// JointStall) names it and says how long it stood — for a streamed motion (the executor's
// read-backs) and for a board move waited for (Arm::wait). Healthy moves, slow ones
// included, never stall.
#include <gtest/gtest.h>

#include <numbers>

#include "arm/motion_executor.hpp"
#include "simulated_arms.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// From `a` to `b` in `T` s, straight in joint space at constant speed.
PlannedMotion straight_motion(std::vector<double> a, std::vector<double> b, double T) {
  PlannedMotion m;
  m.what = "test motion";
  m.duration = T;
  m.sample = [a, b, T](double t, std::vector<double>& p, std::vector<double>& v, std::vector<double>& acc) {
    const double s = std::clamp(t / T, 0.0, 1.0);
    for (std::size_t i = 0; i < a.size(); ++i) {
      p[i] = a[i] + s * (b[i] - a[i]);
      v[i] = (b[i] - a[i]) / T;
      acc[i] = 0;
    }
  };
  return m;
}

class XarmStall : public testing::XarmOnEmulator {
 protected:
  xarm::XarmServos& servos() { return link.emulator().servos(); }
};

TEST_F(XarmStall, AStreamedMotionStopsAndReleasesTheStalledJoint) {
  const auto a = here();
  auto b = a;
  b[2] = a[2] + 20 * kDeg;  // servo4, slowly: 20 deg in 4 s
  // A loose following-error limit (a slow motion, a gentle arm): only the stall watch can stop it.
  ExecutorOptions o;
  o.following_error_angle = 45 * kDeg;
  servos().set_blocked(4, true);
  const TimePoint began = arm.clock().now();
  auto r = execute_motion(arm, straight_motion(a, b, 4.0), o);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::device);
  const JointStall* s = stall_of(r.error());
  ASSERT_NE(s, nullptr) << r.error().message;
  EXPECT_EQ(s->joint, 2);
  EXPECT_EQ(s->name, "servo4");
  EXPECT_GE(s->seconds, 0.5);
  EXPECT_NEAR(s->position, a[2], 0.5 * kDeg);
  EXPECT_GT(s->driven_to - s->position, kStallDrivenAngle);
  EXPECT_NE(r.error().message.find("joint servo4 stalled"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("torque released"), std::string::npos) << r.error().message;
  // Found within the stall time of the joint falling 2 deg behind (0.4 s in), plus a read.
  EXPECT_LT(arm.clock().now() - began, std::chrono::milliseconds(1500));
  // The stalled servo is limp; the others hold where they stand.
  EXPECT_FALSE(servos().torque(4));
  for (int id : {2, 3, 5, 6}) EXPECT_TRUE(servos().torque(rc_board::ServoId(id))) << id;
}

TEST_F(XarmStall, ABoardMoveWaitedForStopsAndReleasesTheStalledJoint) {
  auto targets = std::vector<std::optional<double>>(6);
  targets[1] = here()[1] - 40 * kDeg;  // servo5
  servos().set_blocked(5, true);
  const TimePoint began = arm.clock().now();
  ASSERT_TRUE(arm.move_joints(targets, {.duration = std::chrono::seconds(1)}));
  auto w = arm.wait();
  ASSERT_FALSE(w);
  const JointStall* s = stall_of(w.error());
  ASSERT_NE(s, nullptr) << w.error().message;
  EXPECT_EQ(s->name, "servo5");
  EXPECT_GE(s->seconds, 0.5);
  // Within the stall time (and a read) of the move's end, long before the wait's 10 s.
  EXPECT_LT(arm.clock().now() - began, std::chrono::milliseconds(2200));
  EXPECT_FALSE(servos().torque(5));
  EXPECT_TRUE(servos().torque(4));
}

TEST_F(XarmStall, SlowAndFastHealthyMovesNeverStall) {
  // 1 deg in 5 s: the servo creeps slower than the "moves" threshold per stall time, but is
  // never 2 deg from where the move has it.
  auto targets = std::vector<std::optional<double>>(6);
  targets[2] = here()[2] + 1 * kDeg;
  ASSERT_TRUE(arm.move_joints(targets, {.duration = std::chrono::seconds(5)}));
  auto w = arm.wait();
  EXPECT_TRUE(w) << w.error().message;
  // 90 deg asked in 0.1 s: the servos cannot (0.16 s per 60 deg), so they lag far behind the
  // line, but they move.
  targets[2] = here()[2] - 90 * kDeg;
  ASSERT_TRUE(arm.move_joints(targets, {.duration = std::chrono::milliseconds(100)}));
  w = arm.wait();
  EXPECT_TRUE(w) << w.error().message;
}

class ScaraStall : public testing::ScaraOnBus {};

TEST_F(ScaraStall, ABoardMoveWaitedForStopsAndReleasesTheStalledJoint) {
  auto targets = std::vector<std::optional<double>>(std::size_t(arm.model().joint_count()));
  targets[1] = here()[1] + 30 * kDeg;  // SHOULDER (joint-bus number 2)
  hold_where_it_stands(2);
  ASSERT_TRUE(arm.move_joints(targets, {.duration = std::chrono::seconds(2)}));
  auto w = arm.wait();
  ASSERT_FALSE(w);
  const JointStall* s = stall_of(w.error());
  ASSERT_NE(s, nullptr) << w.error().message;
  EXPECT_EQ(s->name, "SHOULDER");
  EXPECT_GE(s->seconds, 0.5);
  // Its position loop is off (no torque); the others still hold.
  EXPECT_FALSE(sim->joint(2).controller().loop_enabled());
  EXPECT_TRUE(sim->joint(3).controller().loop_enabled());
}

TEST_F(ScaraStall, AStreamedMotionStopsTheStalledJoint) {
  const auto a = here();
  auto b = a;
  b[2] = a[2] - 20 * kDeg;  // UAE (joint-bus number 3), 20 deg in 4 s
  ExecutorOptions o;
  o.following_error_angle = 45 * kDeg;
  hold_where_it_stands(3);
  auto r = execute_motion(arm, straight_motion(a, b, 4.0), o);
  ASSERT_FALSE(r);
  const JointStall* s = stall_of(r.error());
  ASSERT_NE(s, nullptr) << r.error().message;
  EXPECT_EQ(s->name, "UAE");
  EXPECT_FALSE(sim->joint(3).controller().loop_enabled());
}

}  // namespace
}  // namespace armctl::arm

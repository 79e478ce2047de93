// The motion executor on both simulated arms, on simulated time: a stream of short moves
// at the link's rate, pause/resume, stop on the path, abort, following-error stop.
//
// The motions here are hand-made (a cosine blend between two joint sets: smooth, with
// known velocity and acceleration), so that these tests check the executor alone.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "arm/motion_executor.hpp"
#include "simulated_arms.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kPi = std::numbers::pi;

// From `a` to `b` in `T` s with a cosine velocity profile: x(t) = a + (b - a)(1 - cos(pi t/T))/2.
PlannedMotion cosine_motion(std::vector<double> a, std::vector<double> b, double T) {
  PlannedMotion m;
  m.what = "test motion";
  m.duration = T;
  m.sample = [a, b, T](double t, std::vector<double>& p, std::vector<double>& v, std::vector<double>& acc) {
    t = std::clamp(t, 0.0, T);
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double d = b[i] - a[i];
      p[i] = a[i] + d * (1 - std::cos(kPi * t / T)) / 2;
      v[i] = d * kPi / (2 * T) * std::sin(kPi * t / T);
      acc[i] = d * kPi * kPi / (2 * T * T) * std::cos(kPi * t / T);
    }
  };
  return m;
}

// Distance of `q` from the joint-space segment a..b, relative to its length (0 = on it).
double off_line(const std::vector<double>& q, const std::vector<double>& a, const std::vector<double>& b) {
  double dd = 0, dq = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    dd += (b[i] - a[i]) * (b[i] - a[i]);
    dq += (q[i] - a[i]) * (b[i] - a[i]);
  }
  const double f = dq / dd;
  double off = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double e = q[i] - (a[i] + f * (b[i] - a[i]));
    off += e * e;
  }
  return std::sqrt(off / dd);
}

// Options that stall the host once, at nominal time `at`: for `how_long` nothing is sent
// while the device's clock runs on (as when another process takes the CPU).
ExecutorOptions stalling_once(Arm& arm, double at, Duration how_long, bool& stalled) {
  ExecutorOptions o;
  o.on_point = [&arm, at, how_long, &stalled](const MotionProgress& p) {
    if (!stalled && p.t > at) {
      stalled = true;
      (void)arm.device().idle(how_long);
    }
  };
  return o;
}

class RcStream : public testing::XarmOnEmulator {
 protected:
  std::vector<double> goal() {
    auto g = here();
    g[0] = 60 * kDeg;   // servo6
    g[1] = -30 * kDeg;  // servo5
    g[2] = 45 * kDeg;   // servo4
    return g;
  }
};

TEST_F(RcStream, PeriodIsTheWireTimeOfOneMultiServoMove) {
  // Six servos: 7 + 3 x 6 = 25 bytes = 250 bit times at 9600 baud.
  EXPECT_EQ(arm.device().stream_period(false), wire_time(25, 9600));
  using Ms = std::chrono::duration<double, std::milli>;
  EXPECT_NEAR(Ms(arm.device().stream_period(false)).count(), 26.04, 0.01);
}

TEST_F(RcStream, FollowsTheMotionAndArrives) {
  const auto a = here(), b = goal();
  auto m = cosine_motion(a, b, 2.0);
  auto r = execute_motion(arm, m);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
  // 2 s at one point per 26 ms (a read every 200 ms takes a slot): about 70 points.
  EXPECT_GT(r->points, 60u);
  EXPECT_LT(r->points, 80u);
  EXPECT_GE(r->reads, 7u);  // every 200 ms plus the read itself
  EXPECT_EQ(r->late_steps, 0u);  // on time on the simulated clock: nothing held
  EXPECT_EQ(r->held, Duration{0});
  // Read back during the motion: within a few servo units (0.24 deg each) of the plan.
  EXPECT_LT(r->largest_following_error, 2.5 * kDeg) << "joint " << r->largest_following_joint;
  ASSERT_TRUE(arm.wait());
  const auto end = here();
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(end[i], b[i], 0.25 * kDeg) << i;
}

// A host that stalls mid-motion (another process took the CPU for 400 ms) sends nothing
// meanwhile: the arm comes to rest at the last point it got. The motion goes on from there
// instead of jumping 400 ms ahead on the plan (a jump the servos cannot follow, and a
// following-error halt), and the report says how long it was held.
TEST_F(RcStream, AStalledHostHoldsTheMotionInsteadOfJumpingAhead) {
  const auto a = here(), b = goal();
  auto m = cosine_motion(a, b, 2.0);
  bool stalled = false;
  auto r = execute_motion(arm, m, stalling_once(arm, 0.8, std::chrono::milliseconds(400), stalled));
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(stalled);
  EXPECT_TRUE(r->completed);
  EXPECT_EQ(r->late_steps, 1u);
  const double held = std::chrono::duration<double>(r->held).count();
  EXPECT_GT(held, 0.3);  // 400 ms less the last point's lead
  EXPECT_LT(held, 0.45);
  EXPECT_NEAR(std::chrono::duration<double>(r->elapsed).count(), 2.0 + held, 0.06);
  EXPECT_LT(r->largest_following_error, 2.5 * kDeg) << "joint " << r->largest_following_joint;
  ASSERT_TRUE(arm.wait());
  const auto end = here();
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(end[i], b[i], 0.25 * kDeg) << i;
}

TEST_F(RcStream, SpeedOverrideStretchesTime) {
  auto m = cosine_motion(here(), goal(), 1.0);
  ExecutorOptions o;
  o.speed_override = 0.5;
  auto r = execute_motion(arm, m, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_NEAR(std::chrono::duration<double>(r->elapsed).count(), 2.0, 0.06);
  o.speed_override = 0;
  auto refused = execute_motion(arm, m, o);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("override"), std::string::npos);
}

TEST_F(RcStream, StopComesToRestOnThePath) {
  const auto a = here(), b = goal();
  auto m = cosine_motion(a, b, 2.0);
  ExecutorOptions o;
  o.command = [](const MotionProgress& p) { return p.t > 0.8 ? MotionCommand::stop : MotionCommand::none; };
  auto r = execute_motion(arm, m, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->stopped);
  EXPECT_FALSE(r->completed);
  EXPECT_GT(r->t_reached, 0.8);
  EXPECT_LT(r->t_reached, 1.9);
  ASSERT_TRUE(arm.wait());
  const auto end = here();
  // On the joint-space line (within servo resolution), short of the goal.
  EXPECT_LT(off_line(end, a, b), 0.01);
  EXPECT_GT(std::abs(end[0] - b[0]), 2 * kDeg);
  // The stop ramp's extra acceleration stays within the joints' limits: the deceleration
  // read back from the plan's rate is bounded (checked through the elapsed time instead of
  // samples: a ramp that kept the joint within its limit cannot be shorter than this).
  EXPECT_GT(std::chrono::duration<double>(r->elapsed).count(), 0.8 * 1.0 + 0.05);
}

TEST_F(RcStream, PauseHoldsAndResumeFinishes) {
  const auto a = here(), b = goal();
  auto m = cosine_motion(a, b, 2.0);
  ExecutorOptions o;
  std::vector<double> held;
  Duration paused_at{};
  o.command = [&](const MotionProgress& p) {
    if (p.t > 0.6 && !p.paused && paused_at == Duration{0}) {
      paused_at = p.elapsed;
      return MotionCommand::pause;
    }
    if (p.paused && p.elapsed > paused_at + std::chrono::seconds(2)) return MotionCommand::resume;
    return MotionCommand::none;
  };
  std::vector<double> t_while_paused;
  o.on_point = [&](const MotionProgress& p) {
    if (p.paused && p.rate == 0) t_while_paused.push_back(p.t);
  };
  auto r = execute_motion(arm, m, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
  ASSERT_GT(t_while_paused.size(), 10u);
  EXPECT_DOUBLE_EQ(t_while_paused.front(), t_while_paused.back());  // nominal time stood still
  EXPECT_GT(std::chrono::duration<double>(r->elapsed).count(), 3.9);
  ASSERT_TRUE(arm.wait());
  EXPECT_NEAR(here()[0], b[0], 0.25 * kDeg);
}

TEST_F(RcStream, AbortHaltsAtOnce) {
  auto m = cosine_motion(here(), goal(), 2.0);
  ExecutorOptions o;
  o.command = [](const MotionProgress& p) { return p.t > 1.0 ? MotionCommand::abort : MotionCommand::none; };
  auto r = execute_motion(arm, m, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->stopped);
  EXPECT_LT(r->t_reached, 1.05);
}

TEST_F(RcStream, FollowingErrorHaltsAndNamesTheJoint) {
  auto m = cosine_motion(here(), goal(), 2.0);
  link.emulator().servos().set_blocked(4, true);  // servo4: joint index 2
  auto r = execute_motion(arm, m);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::device);
  EXPECT_NE(r.error().message.find("following error on joint servo4"), std::string::npos) << r.error().message;
  // The detail apps branch on: the joint, where it was and where it should have been.
  const FollowingError* f = following_error_of(r.error());
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->joint, 2);
  EXPECT_EQ(f->name, "servo4");
  EXPECT_GT(std::abs(f->planned - f->measured), f->limit);
  EXPECT_GT(f->t, 0);
  EXPECT_LE(f->t, 2.0);
}

// A gripper closing on a part stops short of its plan: that is a grasp, not a fault.
TEST_F(RcStream, AGripperThatStopsShortDoesNotHaltTheMotion) {
  auto b = here();
  b[5] = 60 * kDeg;  // servo1, the gripper, closing
  auto m = cosine_motion(here(), b, 1.0);
  link.emulator().servos().set_blocked(1, true);  // held open by the part
  auto r = execute_motion(arm, m);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
}

TEST_F(RcStream, RefusesAMotionThatDoesNotStartWhereTheArmIs) {
  auto g = goal();
  auto m = cosine_motion(g, g, 1.0);
  const std::size_t before = link.sent.size();
  auto r = execute_motion(arm, m);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("plan it from where the arm stands"), std::string::npos) << r.error().message;
  // Only the position read went out.
  EXPECT_EQ(link.sent.size(), before + 1);
}

class BusStream : public testing::ScaraOnBus {};

TEST_F(BusStream, FollowsTheMotionAndArrives) {
  const auto a = here();
  auto b = a;
  b[1] = a[1] + 30 * kDeg;  // SHOULDER
  b[2] = a[2] - 20 * kDeg;  // UAE
  auto m = cosine_motion(a, b, 2.0);
  auto r = execute_motion(arm, m);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
  EXPECT_GT(r->reads, 20u);
  // The first point also sets every joint's speed (two transactions each): the joints wait
  // for it a few ms, and the plan with them. Nothing else is held.
  EXPECT_LE(r->late_steps, 1u);
  EXPECT_LT(r->held, r->period);
  EXPECT_LT(r->largest_following_error, 1.5 * kDeg) << "joint " << r->largest_following_joint;
  ASSERT_TRUE(arm.wait());
  const auto end = here();
  EXPECT_NEAR(end[1], b[1], 0.1 * kDeg);
  EXPECT_NEAR(end[2], b[2], 0.1 * kDeg);
}

TEST_F(BusStream, StopComesToRestOnThePath) {
  const auto a = here();
  auto b = a;
  b[1] = a[1] + 30 * kDeg;
  b[2] = a[2] - 20 * kDeg;
  auto m = cosine_motion(a, b, 2.0);
  ExecutorOptions o;
  o.command = [](const MotionProgress& p) { return p.t > 0.9 ? MotionCommand::stop : MotionCommand::none; };
  auto r = execute_motion(arm, m, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->stopped);
  ASSERT_TRUE(arm.wait());
  const auto end = here();
  EXPECT_LT(off_line(end, a, b), 0.01);
  EXPECT_GT(std::abs(end[1] - b[1]), 2 * kDeg);
}

}  // namespace
}  // namespace armctl::arm

namespace armctl::arm {
namespace {

TEST_F(BusStream, FollowingErrorHaltsAndNamesTheJoint) {
  const auto a = here();
  auto b = a;
  b[1] = a[1] + 30 * kDeg;  // SHOULDER
  auto m = cosine_motion(a, b, 2.0);
  hold_where_it_stands(2);  // SHOULDER
  auto r = execute_motion(arm, m);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::device);
  EXPECT_NE(r.error().message.find("following error on joint SHOULDER"), std::string::npos) << r.error().message;
}

TEST_F(BusStream, AJointsOwnFollowingErrorLimitReplacesItsKinds) {
  const auto a = here();
  auto b = a;
  b[1] = a[1] + 30 * kDeg;  // SHOULDER, held back by an obstacle as above
  b[2] = a[2] - 20 * kDeg;  // UAE, free
  auto m = cosine_motion(a, b, 2.0);
  hold_where_it_stands(2);
  ExecutorOptions o;
  o.following_error.assign(7, 0.0);
  o.following_error[1] = 1e9;  // SHOULDER not checked: the rest of the motion runs
  o.stall_time = Duration{0};  // nor stalls (a held joint's own test: stall_test.cpp)
  auto r = execute_motion(arm, m, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
  EXPECT_EQ(r->largest_following_joint, 1);
  // UAE held where it stands through a 2 deg move: within the 5 deg default, beyond a
  // 0.5 deg limit of its own.
  hold_where_it_stands(3);
  const auto from = here();
  auto to = from;
  to[2] = from[2] + 2 * kDeg;
  o.following_error[2] = 0.5 * kDeg;
  auto halted = execute_motion(arm, cosine_motion(from, to, 1.0), o);
  ASSERT_FALSE(halted);
  EXPECT_NE(halted.error().message.find("following error on joint UAE"), std::string::npos)
      << halted.error().message;
  ASSERT_NE(following_error_of(halted.error()), nullptr);
  EXPECT_EQ(following_error_of(halted.error())->name, "UAE");
  EXPECT_DOUBLE_EQ(following_error_of(halted.error())->limit, 0.5 * kDeg);
  o.following_error[2] = 0;
  auto within_default = execute_motion(arm, cosine_motion(here(), to, 1.0), o);
  EXPECT_TRUE(within_default) << within_default.error().message;
}

}  // namespace
}  // namespace armctl::arm

namespace armctl::arm {
namespace {

TEST_F(BusStream, PauseHoldsAndResumeFinishes) {
  const auto a = here();
  auto b = a;
  b[1] = a[1] + 30 * kDeg;
  auto m = cosine_motion(a, b, 2.0);
  ExecutorOptions o;
  Duration paused_at{};
  std::vector<double> held;
  o.command = [&](const MotionProgress& p) {
    if (p.t > 0.7 && paused_at == Duration{0}) {
      paused_at = p.elapsed;
      return MotionCommand::pause;
    }
    if (p.paused && p.rate == 0 && held.empty()) held = here();
    if (p.paused && p.elapsed > paused_at + std::chrono::seconds(2)) return MotionCommand::resume;
    return MotionCommand::none;
  };
  auto r = execute_motion(arm, m, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
  ASSERT_FALSE(held.empty());
  EXPECT_GT(std::abs(held[1] - b[1]), 3 * kDeg);  // held short of the goal
  EXPECT_GT(std::chrono::duration<double>(r->elapsed).count(), 3.5);
  ASSERT_TRUE(arm.wait());
  EXPECT_NEAR(here()[1], b[1], 0.1 * kDeg);
}

// The stalled host on the joint bus: the joints ramp to the last target they got and hold
// there; the motion goes on from there when the host is back.
TEST_F(BusStream, AStalledHostHoldsTheMotionInsteadOfJumpingAhead) {
  const auto a = here();
  auto b = a;
  b[1] = a[1] + 30 * kDeg;  // SHOULDER
  b[2] = a[2] - 20 * kDeg;  // UAE
  auto m = cosine_motion(a, b, 2.0);
  bool stalled = false;
  auto r = execute_motion(arm, m, stalling_once(arm, 0.8, std::chrono::milliseconds(400), stalled));
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(stalled);
  EXPECT_TRUE(r->completed);
  EXPECT_GE(r->late_steps, 1u);
  EXPECT_GT(std::chrono::duration<double>(r->held).count(), 0.3);
  EXPECT_LT(r->largest_following_error, 2.5 * kDeg) << "joint " << r->largest_following_joint;
  ASSERT_TRUE(arm.wait());
  const auto end = here();
  EXPECT_NEAR(end[1], b[1], 0.1 * kDeg);
  EXPECT_NEAR(end[2], b[2], 0.1 * kDeg);
}

}  // namespace
}  // namespace armctl::arm

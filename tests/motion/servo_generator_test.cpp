// The servo generator (motion/servo_generator.hpp): every cycle replanned from the state it
// reached, within every limit and the position range, toward velocity or position goals.
#include "motion/servo_generator.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace armctl::motion {
namespace {

constexpr double kDt = 0.004;  // a 250 Hz link

ServoJoint joint(double lower = -2, double upper = 2, double v = 1, double a = 4, double j = 40) {
  return ServoJoint{lower, upper, JerkLimits{v, a, j}};
}

std::vector<ServoGoal> velocities(std::initializer_list<double> v) {
  std::vector<ServoGoal> goals;
  for (double x : v) goals.push_back({ServoGoal::Kind::velocity, x});
  return goals;
}

// Steps `cycles` times, checking the limits at every step; returns false at the first breach.
struct LimitWatch {
  std::vector<ServoJoint> joints;
  double previous_acceleration[kMaxTrajectoryJoints]{};
  testing::AssertionResult step(ServoGenerator& g, std::span<const ServoGoal> goals, double dt = kDt) {
    g.step(goals, dt);
    for (int i = 0; i < g.joints(); ++i) {
      const auto& l = joints[i].limits;
      const double v = g.velocity()[i], a = g.acceleration()[i], p = g.position()[i];
      if (std::abs(v) > l.velocity * (1 + 1e-9) + 1e-12)
        return testing::AssertionFailure() << "joint " << i << " velocity " << v << " beyond " << l.velocity;
      if (std::abs(a) > l.acceleration * (1 + 1e-9) + 1e-12)
        return testing::AssertionFailure() << "joint " << i << " acceleration " << a << " beyond " << l.acceleration;
      if (std::abs(a - previous_acceleration[i]) > l.jerk * dt * (1 + 1e-6) + 1e-9)
        return testing::AssertionFailure() << "joint " << i << " acceleration jumped from " << previous_acceleration[i]
                                           << " to " << a;
      if (p > joints[i].upper + 1e-9 || p < joints[i].lower - 1e-9)
        return testing::AssertionFailure() << "joint " << i << " at " << p << " outside " << joints[i].lower << ".."
                                           << joints[i].upper;
      previous_acceleration[i] = a;
    }
    return testing::AssertionSuccess();
  }
};

TEST(ServoGenerator, AVelocityGoalIsReachedAsFastAsTheLimitsAllowAndHeld) {
  std::vector<ServoJoint> joints{joint()};
  ServoGenerator g;
  ASSERT_TRUE(g.reset(joints, std::vector<double>{-1.5}));
  LimitWatch watch{joints};
  const auto goal = velocities({0.5});
  // 0 -> 0.5 rad/s with a = 4, j = 40: above a^2 / j = 0.4 rad/s the acceleration has a
  // plateau, and the change takes v / a + a / j = 0.225 s.
  int cycles = 0;
  while (std::abs(g.velocity()[0] - 0.5) > 1e-12 && cycles < 1000) {
    ASSERT_TRUE(watch.step(g, goal));
    ++cycles;
  }
  EXPECT_EQ(cycles, int(std::ceil(0.225 / kDt - 1e-9)));
  for (int k = 0; k < 50; ++k) ASSERT_TRUE(watch.step(g, goal));
  EXPECT_DOUBLE_EQ(g.velocity()[0], 0.5);
  EXPECT_DOUBLE_EQ(g.acceleration()[0], 0.0);
}

TEST(ServoGenerator, CyclesOfAnyLengthFollowTheSameMotion) {
  // Replanning from the reached state is consistent: two half steps land where one does.
  std::vector<ServoJoint> joints{joint(), joint(-1, 1, 0.5, 2, 10)};
  ServoGenerator one, two;
  ASSERT_TRUE(one.reset(joints, std::vector<double>{0, 0}));
  ASSERT_TRUE(two.reset(joints, std::vector<double>{0, 0}));
  const auto goal = velocities({0.8, -0.3});
  for (int k = 0; k < 100; ++k) {
    one.step(goal, kDt);
    two.step(goal, kDt / 2);
    two.step(goal, kDt / 2);
    for (int i = 0; i < 2; ++i) {
      ASSERT_NEAR(one.position()[i], two.position()[i], 1e-9) << "cycle " << k;
      ASSERT_NEAR(one.velocity()[i], two.velocity()[i], 1e-9) << "cycle " << k;
    }
  }
}

TEST(ServoGenerator, AJointDrivenIntoTheEndOfItsRangeSlowsDownAndStopsThere) {
  std::vector<ServoJoint> joints{joint(-1, 0.5)};
  ServoGenerator g;
  ASSERT_TRUE(g.reset(joints, std::vector<double>{0}));
  LimitWatch watch{joints};
  const auto goal = velocities({1.0});
  bool was_limited = false;
  for (int k = 0; k < 2000; ++k) {
    ASSERT_TRUE(watch.step(g, goal)) << "cycle " << k;
    was_limited = was_limited || g.limited(0);
  }
  EXPECT_TRUE(was_limited);
  EXPECT_LE(g.position()[0], 0.5);
  EXPECT_GT(g.position()[0], 0.5 - 1e-3);
  EXPECT_LT(std::abs(g.velocity()[0]), 1e-3);
  // And back the other way at full speed.
  const auto back = velocities({-1.0});
  for (int k = 0; k < 200; ++k) ASSERT_TRUE(watch.step(g, back));
  EXPECT_DOUBLE_EQ(g.velocity()[0], -1.0);
}

TEST(ServoGenerator, AJointAlreadyBeyondItsRangeMayOnlyMoveBackIn) {
  std::vector<ServoJoint> joints{joint(-1, 1)};
  ServoGenerator g;
  ASSERT_TRUE(g.reset(joints, std::vector<double>{1.02}));
  for (int k = 0; k < 100; ++k) g.step(velocities({0.5}), kDt);
  EXPECT_DOUBLE_EQ(g.position()[0], 1.02);
  EXPECT_TRUE(g.limited(0));
  for (int k = 0; k < 100; ++k) g.step(velocities({-0.5}), kDt);
  EXPECT_LT(g.position()[0], 1.0);
}

TEST(ServoGenerator, CommandsThatStopArrivingBringItToRestWithinOneVelocityChange) {
  std::vector<ServoJoint> joints{joint(), joint()};
  ServoGenerator g;
  ASSERT_TRUE(g.reset(joints, std::vector<double>{0, 0}));
  LimitWatch watch{joints};
  for (int k = 0; k < 100; ++k) ASSERT_TRUE(watch.step(g, velocities({0.6, -0.6})));
  const double braking = stopping_displacement(g.velocity()[0], g.acceleration()[0], joints[0].limits);
  const double from = g.position()[0];
  int cycles = 0;
  while (!g.at_rest() && cycles < 1000) {
    ASSERT_TRUE(watch.step(g, velocities({0, 0})));
    ++cycles;
  }
  // 0.6 rad/s to rest: 0.6 / 4 + 4 / 40 = 0.25 s.
  EXPECT_EQ(cycles, int(std::ceil(0.25 / kDt - 1e-9)));
  EXPECT_NEAR(g.position()[0] - from, braking, 1e-9);
  EXPECT_NEAR(g.position()[1], -g.position()[0], 1e-12);
}

TEST(ServoGenerator, PositionGoalsArriveTogetherInTheTimeOptimalDuration) {
  std::vector<ServoJoint> joints{joint(), joint(), joint(-2, 2, 0.5, 2, 20)};
  ServoGenerator g;
  ASSERT_TRUE(g.reset(joints, std::vector<double>{0, 0, 0}));
  const std::vector<ServoGoal> goals{{ServoGoal::Kind::position, 1.0},
                                     {ServoGoal::Kind::position, -0.2},
                                     {ServoGoal::Kind::position, 0.3}};
  TrajectoryInput in;
  in.joints = 3;
  in.target_position = {1.0, -0.2, 0.3};
  for (int i = 0; i < 3; ++i) {
    in.max_velocity[i] = joints[i].limits.velocity;
    in.max_acceleration[i] = joints[i].limits.acceleration;
    in.max_jerk[i] = joints[i].limits.jerk;
  }
  Trajectory optimal;
  ASSERT_TRUE(calculate_trajectory(in, optimal));
  LimitWatch watch{joints};
  int cycles = 0;
  while (!g.at_rest() || cycles == 0) {
    ASSERT_TRUE(watch.step(g, goals));
    ASSERT_LT(++cycles, 10000);
    // Replanned every cycle, the slowest joint stays on its one optimal profile (the others
    // may pick another of the profiles that arrive at the same time).
    ASSERT_NEAR(g.position()[0], optimal.at(cycles * kDt).position[0], 1e-7) << "cycle " << cycles;
  }
  EXPECT_EQ(cycles, int(std::ceil(optimal.duration() / kDt - 1e-9)));
  EXPECT_DOUBLE_EQ(g.position()[0], 1.0);
  EXPECT_DOUBLE_EQ(g.position()[1], -0.2);
}

TEST(ServoGenerator, APositionGoalBeyondTheRangeStopsAtItsEnd) {
  std::vector<ServoJoint> joints{joint(-1, 1)};
  ServoGenerator g;
  ASSERT_TRUE(g.reset(joints, std::vector<double>{0}));
  const std::vector<ServoGoal> far{{ServoGoal::Kind::position, 5.0}};
  for (int k = 0; k < 1000; ++k) g.step(far, kDt);
  EXPECT_DOUBLE_EQ(g.position()[0], 1.0);
  EXPECT_TRUE(g.limited(0));
}

TEST(ServoGenerator, APositionGoalsSpeedCapHoldsAndOneThatComesDownIsSlowedTo) {
  // Two joints to far goals, capped at 0.3 and 0.2 rad/s (their limit 1): neither goes
  // faster, both arrive. Then, halfway back at full speed, the cap comes down to 0.25: each
  // slows to it within one velocity change, keeping its direction, and still arrives.
  std::vector<ServoJoint> joints{joint(), joint()};
  ServoGenerator g;
  ASSERT_TRUE(g.reset(joints, std::vector<double>{0, 0}));
  LimitWatch watch{joints};
  std::vector<ServoGoal> goals{{ServoGoal::Kind::position, 1.5, 0.3}, {ServoGoal::Kind::position, -1.0, 0.2}};
  const auto at = [&](double a, double b) { return std::abs(g.position()[0] - a) < 1e-9 && std::abs(g.position()[1] - b) < 1e-9; };
  int cycles = 0;
  for (; cycles < 5000 && !at(1.5, -1.0); ++cycles) {
    ASSERT_TRUE(watch.step(g, goals));
    ASSERT_LE(std::abs(g.velocity()[0]), 0.3 + 1e-12);
    ASSERT_LE(std::abs(g.velocity()[1]), 0.2 + 1e-12);
  }
  EXPECT_LT(cycles, 5000);
  EXPECT_GT(cycles * kDt, 1.5 / 0.3);  // slower than its own limit would allow
  goals = {{ServoGoal::Kind::position, -1.5}, {ServoGoal::Kind::position, 1.0}};
  while (g.position()[0] > 0) ASSERT_TRUE(watch.step(g, goals));
  ASSERT_GT(std::abs(g.velocity()[0]), 0.9);
  goals[0].max_speed = goals[1].max_speed = 0.25;
  // One velocity change from 1 to 0.25 rad/s (a = 4, j = 40): 0.29 s.
  for (int k = 0; k < int(0.35 / kDt); ++k) {
    ASSERT_TRUE(watch.step(g, goals));
    ASSERT_LT(g.velocity()[0], 0);  // never turned back
  }
  for (cycles = 0; cycles < 5000 && !at(-1.5, 1.0); ++cycles) {
    ASSERT_TRUE(watch.step(g, goals));
    ASSERT_LE(std::abs(g.velocity()[0]), 0.25 + 1e-12);
    ASSERT_LE(std::abs(g.velocity()[1]), 0.25 + 1e-12);
  }
  EXPECT_LT(cycles, 5000);
}

TEST(ServoGenerator, RandomGoalsOfBothKindsNeverBreakALimit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + int(u(rng) * 7);
    std::vector<ServoJoint> joints;
    std::vector<double> start;
    for (int i = 0; i < n; ++i) {
      const double lower = -0.5 - 2 * u(rng), upper = 0.5 + 2 * u(rng);
      joints.push_back(joint(lower, upper, 0.1 + 2 * u(rng), 0.5 + 10 * u(rng), 5 + 100 * u(rng)));
      start.push_back(lower + (upper - lower) * u(rng));
    }
    ServoGenerator g;
    ASSERT_TRUE(g.reset(joints, start));
    LimitWatch watch{joints};
    std::vector<ServoGoal> goals(static_cast<std::size_t>(n));
    for (int k = 0; k < 600; ++k) {
      if (k % 40 == 0)
        for (int i = 0; i < n; ++i) {
          const bool position = u(rng) < 0.4;
          goals[std::size_t(i)] = {position ? ServoGoal::Kind::position : ServoGoal::Kind::velocity,
                                   position ? -4 + 8 * u(rng) : (-1.5 + 3 * u(rng)) * joints[std::size_t(i)].limits.velocity};
        }
      ASSERT_TRUE(watch.step(g, goals, 0.002 + 0.02 * u(rng))) << "trial " << trial << " cycle " << k;
    }
  }
}

TEST(ServoGenerator, ResetRefusesWhatItCannotDrive) {
  ServoGenerator g;
  std::vector<ServoJoint> bad_limits{joint(-1, 1, 0, 1, 1)};
  auto e = g.reset(bad_limits, std::vector<double>{0});
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("joint 1: velocity, acceleration and jerk limits"), std::string::npos);
  std::vector<ServoJoint> backwards{joint(1, -1)};
  EXPECT_FALSE(g.reset(backwards, std::vector<double>{0}));
  std::vector<ServoJoint> one{joint()};
  EXPECT_FALSE(g.reset(one, std::vector<double>{NAN}));
  EXPECT_FALSE(g.reset(one, std::vector<double>{0, 0}));
  EXPECT_FALSE(g.reset(std::vector<ServoJoint>(8, joint()), std::vector<double>(8, 0.0)));
}

TEST(ServoGenerator, StoppingSpeedStopsExactlyWithinTheDistance) {
  const JerkLimits limits{5, 2, 10};
  for (double d : {1e-6, 1e-3, 0.01, 0.1, 0.4, 1.0, 3.0}) {
    const double v = stopping_speed(d, limits);
    if (v < limits.velocity) EXPECT_NEAR(stopping_displacement(v, 0, limits), d, 1e-9 * (1 + d)) << d;
    else EXPECT_LE(stopping_displacement(v, 0, limits), d);
  }
  EXPECT_EQ(stopping_speed(0, limits), 0);
  EXPECT_EQ(stopping_speed(-1, limits), 0);
}

}  // namespace
}  // namespace armctl::motion

// The trajectory generator (docs/trajectories.md): hand-worked cases, validation,
// synchronization, waypoints, and 100,000 random cases checked analytically.
#include "motion/trajectory.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "trajectory_random_cases.hpp"

namespace armctl::motion {
namespace {

TrajectoryInput one_joint(double vmax, double amax, double jmax) {
  TrajectoryInput in;
  in.joints = 1;
  in.max_velocity[0] = vmax, in.max_acceleration[0] = amax, in.max_jerk[0] = jmax;
  return in;
}

double calculated_duration(const TrajectoryInput& in) {
  Trajectory t;
  const Status s = calculate_trajectory(in, t);
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  EXPECT_EQ(testing::check_trajectory(in, t), "");
  return t.duration();
}

TEST(TrajectoryHandCases, RestToRestReachingEveryLimit) {
  // vmax 2, amax 1, jerk 1: to 2 m/s is jerk 1 s (a = 1, v = 0.5), hold 1 s (v = 1.5),
  // jerk -1 s (v = 2): 3 s over 3 m (mean velocity 1 by symmetry). Braking mirrors it.
  // 10 m = 3 + 3 + a cruise of 4 m at 2 m/s = 2 s: 8 s.
  TrajectoryInput in = one_joint(2, 1, 1);
  in.target_position[0] = 10;
  EXPECT_NEAR(calculated_duration(in), 8.0, 1e-12);
  in.target_position[0] = -10;  // the same backwards
  EXPECT_NEAR(calculated_duration(in), 8.0, 1e-12);
  EXPECT_NEAR(rest_to_rest_time(10, {2, 1, 1}), 8.0, 1e-12);
}

TEST(TrajectoryHandCases, TriangularAcceleration) {
  // 0.25 m: jerk 1 for 0.5 s (a 0.5, v 0.125), -1 for 0.5 s (v 0.25) covers 0.125 m; back
  // down the same: 2 s, peak 0.25 m/s, peak acceleration 0.5 (amax 1 not reached).
  TrajectoryInput in = one_joint(2, 1, 1);
  in.target_position[0] = 0.25;
  Trajectory t;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_NEAR(t.duration(), 2.0, 1e-12);
  const TrajectoryExtrema e = t.extrema();
  EXPECT_NEAR(e.max_abs_velocity[0], 0.25, 1e-12);
  EXPECT_NEAR(e.max_abs_acceleration[0], 0.5, 1e-12);
  EXPECT_NEAR(e.max_position[0], 0.25, 1e-12);
  EXPECT_NEAR(e.min_position[0], 0.0, 1e-12);
  EXPECT_NEAR(t.at(1.0).velocity[0], 0.25, 1e-12);
  EXPECT_NEAR(t.at(1.0).position[0], 0.125, 1e-12);
}

TEST(TrajectoryHandCases, TrapezoidalAccelerationWithoutCruise) {
  // 3 m: a plateau at amax but the peak vp below vmax: each change takes vp + 1 s and
  // covers vp (vp + 1) / 2, so vp^2 + vp = 3, vp = (sqrt 13 - 1) / 2, T = 1 + sqrt 13.
  TrajectoryInput in = one_joint(2, 1, 1);
  in.target_position[0] = 3;
  EXPECT_NEAR(calculated_duration(in), 1 + std::sqrt(13.0), 1e-12);
}

TEST(TrajectoryHandCases, CruisingOnAtTopSpeedAndBrakingToAStop) {
  // Already at 2 m/s, 10 m on, to arrive at 2 m/s: a pure cruise, 5 s.
  TrajectoryInput in = one_joint(2, 1, 1);
  in.velocity[0] = 2, in.target_velocity[0] = 2, in.target_position[0] = 10;
  EXPECT_NEAR(calculated_duration(in), 5.0, 1e-12);
  // From 2 m/s to rest exactly at the braking distance (3 m, 3 s, as above).
  in.target_velocity[0] = 0, in.target_position[0] = 3;
  EXPECT_NEAR(calculated_duration(in), 3.0, 1e-9);
}

TEST(TrajectoryHandCases, AJointAlreadyOnItsTargetWaits) {
  TrajectoryInput in = one_joint(2, 1, 1);
  in.joints = 2;
  in.max_velocity[1] = 2, in.max_acceleration[1] = 1, in.max_jerk[1] = 1;
  in.target_position[1] = 10;
  Trajectory t;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_NEAR(t.duration(), 8.0, 1e-12);
  EXPECT_EQ(t.extrema().max_abs_velocity[0], 0);
  EXPECT_EQ(testing::check_trajectory(in, t), "");
}

TEST(TrajectoryHandCases, MinDurationStretchesEveryJoint) {
  TrajectoryInput in = one_joint(2, 1, 1);
  in.target_position[0] = 10;
  in.min_duration = 20;
  Trajectory t;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_NEAR(t.duration(), 20.0, 1e-12);
  EXPECT_EQ(testing::check_trajectory(in, t), "");
  EXPECT_LT(t.extrema().max_abs_velocity[0], 2.0);
}

TEST(TrajectoryHandCases, ADurationOutsideTheFamilyIsBlended) {
  // At 2 m/s, 3.5 m to go, to stop there (vmax 2, amax 1, jerk 1). Fastest: cruise 0.25 s
  // (0.5 m), brake 2 -> 0 in 3 s over 3 m: 3.25 s. The family (a peak velocity vp, a
  // cruise there) has nothing just above 3.25 s: braking 2 -> vp -> 0 in two steps covers
  // too much ground for any vp until 3.922 s (the profile with no cruise at vp < 1, where
  // 2 -> vp takes 3 - vp s over (2 + vp)(3 - vp)/2 m and vp -> 0 takes 2 sqrt(vp) s over
  // vp^1.5 m: 3.5 m when -vp^2 + 2 vp^1.5 + vp - 1 = 0, T = 3 - vp + 2 sqrt(vp)). But 3.5 s
  // is possible: a longer cruise at 2 m/s covers more (4 m), braking at once covers less
  // (3 m, then at rest): the blend of those two lands on 3.5 m in 3.5 s.
  TrajectoryInput in = one_joint(2, 1, 1);
  in.velocity[0] = 2, in.target_position[0] = 3.5;
  EXPECT_NEAR(calculated_duration(in), 3.25, 1e-12);
  in.min_duration = 3.5;  // the old gap
  EXPECT_NEAR(calculated_duration(in), 3.5, 1e-12);
  // Synchronized with a joint whose own minimum falls there: rest to rest over 1.5 m
  // (triangular: vp = cbrt(1.5^2 / 4), T = 4 sqrt(vp) = 3.63 s): that joint's minimum.
  in.min_duration = 0;
  in.joints = 2;
  in.max_velocity[1] = 2, in.max_acceleration[1] = 1, in.max_jerk[1] = 1;
  in.target_position[1] = 1.5;
  EXPECT_NEAR(calculated_duration(in), rest_to_rest_time(1.5, {2, 1, 1}), 1e-12);
}

TEST(TrajectoryHandCases, ABlockedIntervalIsSkipped) {
  // Cruising at 2 m/s (vmax 2, amax 1, jerk 1), 1 m ahead, to pass there at 2 m/s: 0.5 s.
  // Taking longer means dipping below 2 m/s and back up (it cannot go faster); the least
  // ground in T is the dip 2 -> 2 - u -> 2 with no cruise. Triangles (u <= 1): T = 4 sqrt(u)
  // over 2 T - T^3 / 32 m, more than 1 m for every T up to 4 s; trapezoids: T = 2 (u + 1)
  // over (4 - u)(u + 1) m, 1 m at u^2 - 3 u - 3 = 0, u = (3 + sqrt 21) / 2. So the
  // durations in (0.5 s, 5 + sqrt 21 s = 9.58 s) are blocked: every motion covers too much.
  const double gap_end = 5 + std::sqrt(21.0);
  TrajectoryInput in = one_joint(2, 1, 1);
  in.velocity[0] = 2, in.target_velocity[0] = 2, in.target_position[0] = 1;
  EXPECT_NEAR(calculated_duration(in), 0.5, 1e-12);
  in.min_duration = 1;  // inside the gap
  EXPECT_NEAR(calculated_duration(in), gap_end, 1e-9);
  // Synchronized with a joint whose own minimum falls in the gap: rest to rest over 5 m
  // (vp^2 + vp = 5, T = 2 (vp + 1) = 1 + sqrt 21 = 5.58 s): the same.
  in.min_duration = 0;
  in.joints = 2;
  in.max_velocity[1] = 2, in.max_acceleration[1] = 1, in.max_jerk[1] = 1;
  in.target_position[1] = 5;
  EXPECT_NEAR(rest_to_rest_time(5, {2, 1, 1}), 1 + std::sqrt(21.0), 1e-12);
  EXPECT_NEAR(calculated_duration(in), gap_end, 1e-9);
}

TEST(TrajectoryHandCases, TimeIsClampedAndStorageReused) {
  TrajectoryInput in = one_joint(2, 1, 1);
  in.target_position[0] = 10;
  Trajectory t;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_EQ(t.at(-1).position[0], 0);
  EXPECT_NEAR(t.at(100).position[0], 10, 1e-12);
  EXPECT_EQ(t.sections(), 1);
  EXPECT_EQ(t.section_end(0), t.duration());
  const JerkSegment* storage = t.segments(0, 0).data();
  in.target_position[0] = -4;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_EQ(t.segments(0, 0).data(), storage);  // no new storage for as many sections
  EXPECT_TRUE(t.segments(1, 0).empty());
  EXPECT_TRUE(t.segments(0, 1).empty());
  EXPECT_EQ(Trajectory{}.duration(), 0);
}

TEST(TrajectorySynchronization, RestToRestIsAStraightLine) {
  // Three joints with equal limits, rest to rest: phase synchronized, every joint the same
  // fraction of its way at every instant, in the slowest joint's minimum time.
  TrajectoryInput in = one_joint(2, 1, 1);
  in.joints = 3;
  for (int i = 1; i < 3; ++i)
    in.max_velocity[i] = 2, in.max_acceleration[i] = 1, in.max_jerk[i] = 1;
  in.position = {1, 2, 3};
  in.target_position = {11, 0, 3.5};
  Trajectory t;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_EQ(testing::check_trajectory(in, t), "");
  EXPECT_NEAR(t.duration(), 8.0, 1e-12);  // joint 0's 10 m, worked above
  for (double f : {0.1, 0.25, 0.5, 0.8, 0.95}) {
    const TrajectoryState s = t.at(f * t.duration());
    const double share = (s.position[0] - 1) / 10;
    EXPECT_NEAR((s.position[1] - 2) / -2, share, 1e-12);
    EXPECT_NEAR((s.position[2] - 3) / 0.5, share, 1e-12);
  }
  // One joint already moving: not collinear, time synchronized instead (each joint its own
  // profile shape), still arriving together.
  in.velocity[2] = 0.3;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_EQ(testing::check_trajectory(in, t), "");
  const TrajectoryState s = t.at(0.25 * t.duration());
  EXPECT_GT(std::abs((s.position[2] - 3) / 0.5 - (s.position[0] - 1) / 10), 1e-3);
}

// Validation: every refusal is invalid_argument, names what was wrong, and leaves `out`.
std::string refusal(const TrajectoryInput& in) {
  Trajectory t;
  TrajectoryInput ok = one_joint(2, 1, 1);
  ok.target_position[0] = 1;
  EXPECT_TRUE(calculate_trajectory(ok, t).ok());
  const double before = t.duration();
  const Status s = calculate_trajectory(in, t);
  if (s.ok()) return "accepted";
  EXPECT_EQ(t.duration(), before);
  EXPECT_EQ(s.error().kind, ErrorKind::invalid_argument);
  return s.error().message;
}

TEST(TrajectoryValidation, RefusesWhatIsNotAllowed) {
  using ::testing::HasSubstr;
  const TrajectoryInput base = [] {
    TrajectoryInput in;
    in.joints = 3;
    for (int i = 0; i < 3; ++i)
      in.max_velocity[i] = 2, in.max_acceleration[i] = 1, in.max_jerk[i] = 1;
    in.target_position = {1, 2, 3};
    return in;
  }();
  EXPECT_EQ(refusal(base), "accepted");
  TrajectoryInput in = base;
  in.joints = 0;
  EXPECT_THAT(refusal(in), HasSubstr("joint count 0 (allowed: 1..7)"));
  in.joints = 8;
  EXPECT_THAT(refusal(in), HasSubstr("joint count 8"));
  in = base, in.max_jerk[2] = 0;
  EXPECT_THAT(refusal(in), HasSubstr("joint 2: max_jerk 0"));
  in = base, in.max_velocity[1] = -1;
  EXPECT_THAT(refusal(in), HasSubstr("joint 1: max_velocity -1"));
  in = base, in.max_acceleration[0] = INFINITY;
  EXPECT_THAT(refusal(in), HasSubstr("joint 0: max_acceleration inf"));
  in = base, in.position[1] = NAN;
  EXPECT_THAT(refusal(in), HasSubstr("joint 1: position nan"));
  in = base, in.target_position[2] = -INFINITY;
  EXPECT_THAT(refusal(in), HasSubstr("joint 2: target_position -inf"));
  in = base, in.velocity[2] = 2.5;
  EXPECT_THAT(refusal(in), HasSubstr("joint 2: velocity 2.5 is beyond max_velocity 2"));
  in = base, in.target_velocity[0] = -3;
  EXPECT_THAT(refusal(in), HasSubstr("joint 0: target_velocity -3 is beyond max_velocity 2"));
  in = base, in.acceleration[1] = 1.5;
  EXPECT_THAT(refusal(in), HasSubstr("joint 1: acceleration 1.5 is beyond max_acceleration 1"));
  // 1.8 m/s while accelerating at 1 m/s^2: bringing a to 0 at jerk 1 adds 0.5 m/s.
  in = base, in.velocity[1] = 1.8, in.acceleration[1] = 1;
  EXPECT_THAT(refusal(in), HasSubstr("joint 1: velocity 1.8 with acceleration 1 must reach 2.3"));
  in.acceleration[1] = -1;  // braking: fine
  EXPECT_EQ(refusal(in), "accepted");
  in = base, in.min_duration = -1;
  EXPECT_THAT(refusal(in), HasSubstr("min_duration -1"));
  in = base, in.min_duration = NAN;
  EXPECT_THAT(refusal(in), HasSubstr("min_duration nan"));
  in = base, in.max_velocity[0] = 1e13;
  EXPECT_THAT(refusal(in),
              HasSubstr("joint 0: max_velocity 10000000000000 (allowed: finite, 1e-09..1e+12)"));
  const std::vector<JointArray> waypoints{{0.5, 1, 1}, {0.7, NAN, 2}};
  in = base, in.waypoints = waypoints;
  EXPECT_THAT(refusal(in), HasSubstr("waypoint 1: joint 1: position nan"));
  // Joints beyond `joints` are not looked at.
  in = base, in.max_jerk[5] = NAN;
  EXPECT_EQ(refusal(in), "accepted");
}

TEST(TrajectoryWaypoints, PassedThroughWithoutStopping) {
  // One joint 0 -> 1 -> 3 and another 0 -> -1 -> -1.5: both keep going at the waypoint.
  TrajectoryInput in = one_joint(2, 1, 1);
  in.joints = 2;
  in.max_velocity[1] = 2, in.max_acceleration[1] = 1, in.max_jerk[1] = 1;
  const std::vector<JointArray> waypoints{{1, -1}};
  in.waypoints = waypoints;
  in.target_position = {3, -1.5};
  Trajectory t;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_EQ(testing::check_trajectory(in, t), "");
  ASSERT_EQ(t.sections(), 2);
  const TrajectoryState w = t.at(t.section_end(0));
  EXPECT_NEAR(w.position[0], 1, 1e-9);
  EXPECT_NEAR(w.position[1], -1, 1e-9);
  EXPECT_GT(w.velocity[0], 0.1);
  EXPECT_LT(w.velocity[1], -0.1);
  EXPECT_NEAR(w.acceleration[0], 0, 1e-12);
  JointArray chosen[1];
  waypoint_velocities(in, chosen);
  EXPECT_NEAR(w.velocity[0], chosen[0][0], 1e-12);
  // Faster than stopping there: the same two moves rest to rest.
  TrajectoryInput first = in, second = in;
  first.waypoints = {}, first.target_position = {1, -1};
  second.waypoints = {}, second.position = {1, -1};
  Trajectory a, b;
  ASSERT_TRUE(calculate_trajectory(first, a).ok());
  ASSERT_TRUE(calculate_trajectory(second, b).ok());
  EXPECT_LT(t.duration(), a.duration() + b.duration());
  // Where a joint reverses, it stops at the waypoint: 0 -> 1 -> 0.
  in.target_position = {0, -1.5};
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_EQ(testing::check_trajectory(in, t), "");
  EXPECT_EQ(t.at(t.section_end(0)).velocity[0], 0);
  EXPECT_NEAR(t.extrema().max_position[0], 1, 1e-9);
}

TEST(TrajectoryWaypoints, ManyWaypointsAndMinDuration) {
  TrajectoryInput in = one_joint(1, 2, 5);
  in.joints = 3;
  for (int i = 1; i < 3; ++i)
    in.max_velocity[i] = 1.5, in.max_acceleration[i] = 1, in.max_jerk[i] = 3;
  std::vector<JointArray> waypoints;
  for (int k = 1; k <= 20; ++k) waypoints.push_back({0.3 * k, std::sin(k), k % 3 == 0 ? 1.0 : 0.0});
  in.waypoints = waypoints;
  in.target_position = {7, 0, 0};
  Trajectory t;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_EQ(testing::check_trajectory(in, t), "");
  EXPECT_EQ(t.sections(), 21);
  const double fastest = t.duration();
  in.min_duration = 2 * fastest;
  ASSERT_TRUE(calculate_trajectory(in, t).ok());
  EXPECT_EQ(testing::check_trajectory(in, t), "");
  EXPECT_GE(t.duration(), 2 * fastest);
  EXPECT_LT(t.duration(), 2.2 * fastest);
}

TEST(TrajectoryRandom, WithWaypoints) {
  // 5,000 random cases, each with 1..4 random waypoints near the straight line.
  testing::RandomCases cases(99);
  std::mt19937_64 rng(5);
  Trajectory t;
  int failures = 0;
  for (int c = 0; c < 5000 && failures < 3; ++c) {
    TrajectoryInput in = cases.next();
    std::vector<JointArray> waypoints(std::uniform_int_distribution<int>(1, 4)(rng));
    for (std::size_t k = 0; k < waypoints.size(); ++k)
      for (int i = 0; i < in.joints; ++i) {
        const double f = double(k + 1) / double(waypoints.size() + 1);
        waypoints[k][i] = in.position[i] + f * (in.target_position[i] - in.position[i]) +
                          std::uniform_real_distribution<double>(-0.5, 0.5)(rng);
      }
    in.waypoints = waypoints;
    const Status s = calculate_trajectory(in, t);
    const std::string why = s.ok() ? testing::check_trajectory(in, t) : s.error().message;
    if (!why.empty())
      ++failures, ADD_FAILURE() << "case " << c << ": " << why << "\n" << testing::describe(in);
  }
}

TEST(TrajectoryRandom, ExtremeAllowedInputsStayFinite) {
  // Limits anywhere in 1e-9..1e12 and positions up to 1e12 (all that validation lets in):
  // accuracy is not asked of these, but nothing may come out NaN or infinite.
  std::mt19937_64 rng(3);
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
  };
  auto signed_value = [&](double magnitude) {
    return std::uniform_int_distribution<int>(0, 1)(rng) ? magnitude : -magnitude;
  };
  Trajectory t;
  for (int c = 0; c < 20000; ++c) {
    TrajectoryInput in;
    in.joints = std::uniform_int_distribution<int>(1, 7)(rng);
    for (int i = 0; i < in.joints; ++i) {
      const double vmax = log_uniform(1e-9, 1e12), amax = log_uniform(1e-9, 1e12),
                   jmax = log_uniform(1e-9, 1e12);
      in.max_velocity[i] = vmax, in.max_acceleration[i] = amax, in.max_jerk[i] = jmax;
      in.position[i] = signed_value(log_uniform(1e-12, 1e12));
      in.target_position[i] = signed_value(log_uniform(1e-12, 1e12));
      in.velocity[i] = signed_value(vmax * std::uniform_real_distribution<double>(0, 1)(rng));
      in.target_velocity[i] =
          signed_value(vmax * std::uniform_real_distribution<double>(0, 1)(rng));
    }
    const Status s = calculate_trajectory(in, t);
    ASSERT_TRUE(s.ok()) << s.error().message;
    ASSERT_TRUE(std::isfinite(t.duration())) << testing::describe(in);
    for (double f : {0.0, 0.3, 0.7, 1.0}) {
      const TrajectoryState st = t.at(f * t.duration());
      for (int i = 0; i < in.joints; ++i)
        ASSERT_TRUE(std::isfinite(st.position[i]) && std::isfinite(st.velocity[i]) &&
                    std::isfinite(st.acceleration[i]))
            << testing::describe(in);
    }
  }
}

TEST(TrajectoryRandom, HundredThousandCases) {
  testing::run_random_cases(20261201, 100000);
}

}  // namespace
}  // namespace armctl::motion

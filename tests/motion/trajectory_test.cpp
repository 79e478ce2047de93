// The trajectory generator (docs/trajectories.md): hand-worked cases, validation,
// synchronization, waypoints, and 100,000 random cases checked analytically.
#include "motion/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(TrajectoryRandom, HundredThousandCases) { testing::run_random_cases(20261201, 100000); }

}  // namespace
}  // namespace armctl::motion

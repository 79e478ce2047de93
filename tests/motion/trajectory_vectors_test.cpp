// The synchronized optimum against Ruckig's (../shared/vectors/trajectory-sync-7dof.json):
// 961 seven-joint cases, 61 of them "hard" (the slowest joint's duration outside another
// joint's profile family). Every case at Ruckig's duration within 1e-6 s either way (longer
// is not optimal; shorter would mean a broken limit), every joint within its limits at each
// segment's analytic extrema and on its target at the end (trajectory_random_cases.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "trajectory_brute_force.hpp"
#include "trajectory_random_cases.hpp"
#include "trajectory_vectors.hpp"

namespace armctl::motion {
namespace {

TEST(TrajectoryVectors, SevenJointsAtRuckigsOptimum) {
  const auto vectors = testing::load_sync_vectors(testing::sync_vectors_path());
  ASSERT_EQ(vectors.size(), 961u);
  // JSON has fields af (target acceleration): the generator's is always 0, and so are theirs.
  Trajectory traj;
  int longer = 0, shorter = 0, at_optimum = 0, hard = 0, hard_at_optimum = 0;
  double worst_excess = 0, worst_deficit = 0;
  for (const auto& v : vectors) {
    const Status s = calculate_trajectory(v.in, traj);
    ASSERT_TRUE(s.ok()) << v.name << ": " << s.error().message;
    const std::string why = testing::check_trajectory(v.in, traj);
    EXPECT_EQ(why, "") << v.name << "\n" << testing::describe(v.in);
    const double diff = traj.duration() - v.duration;
    worst_excess = std::max(worst_excess, diff);
    worst_deficit = std::max(worst_deficit, -diff);
    hard += v.hard;
    if (diff > 1e-6) {
      if (++longer <= 5)
        ADD_FAILURE() << v.name << ": " << traj.duration() << " s, optimum " << v.duration << " s\n"
                      << testing::describe(v.in);
    } else if (diff < -1e-6) {
      if (++shorter <= 5)
        ADD_FAILURE() << v.name << ": " << traj.duration() << " s, shorter than the optimum "
                      << v.duration << " s\n"
                      << testing::describe(v.in);
    } else {
      ++at_optimum;
      hard_at_optimum += v.hard;
    }
  }
  std::printf(
      "vectors: %zu cases, %d at the optimum (%d of %d hard), %d longer, %d shorter; largest "
      "excess %.3g s, largest deficit %.3g s\n",
      vectors.size(), at_optimum, hard_at_optimum, hard, longer, shorter, worst_excess,
      worst_deficit);
  EXPECT_EQ(longer, 0);
  EXPECT_EQ(shorter, 0);
}

TEST(TrajectoryVectors, TheIndependentTestAgreesWithRuckig) {
  // The brute force's test of which durations a joint can take (trajectory_brute_force.hpp),
  // checked on its own against Ruckig: every joint can take Ruckig's duration, and 1e-6 s
  // less is impossible for at least one joint.
  int disagree = 0;
  for (const auto& v : testing::load_sync_vectors(testing::sync_vectors_path())) {
    bool all_at = true, all_before = true;
    for (int i = 0; i < v.in.joints; ++i) {
      all_at = all_at && testing::joint_can_take(v.in, i, v.duration, 1e-9);
      all_before = all_before && testing::joint_can_take(v.in, i, v.duration - 1e-6, -1e-12);
    }
    if (!all_at || all_before) {
      if (++disagree <= 5)
        ADD_FAILURE() << v.name << ": " << (all_at ? "shorter possible" : "a joint cannot take it");
    }
  }
  EXPECT_EQ(disagree, 0);
}

}  // namespace
}  // namespace armctl::motion

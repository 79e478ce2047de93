// Time-optimality of the trajectory generator against a brute force that knows nothing of
// its profile family (trajectory_brute_force.hpp, docs/trajectories.md "Optimality check").
#include <gtest/gtest.h>

#include "trajectory_brute_force.hpp"

namespace armctl::motion {
namespace {

TEST(TrajectoryOptimality, OneJointMatchesTheBruteForce) {
  testing::check_one_joint_optimality(7, 60);
}

TEST(TrajectoryOptimality, TwoJointsSynchronizeAtTheSlowerOptimum) {
  testing::check_two_joint_optimality(8, 30);
}

TEST(TrajectoryOptimality, SynchronizedCasesAtTheOptimum) {
  // 100,000 cases of 2..7 joints, each against the independent test of which durations a
  // joint can take (trajectory_brute_force.hpp): no shorter duration possible for all.
  testing::check_synchronized_optimality(9, 100000, 8);
}

TEST(TrajectoryOptimality, ExtremalMotionsMatchTheIndependentOnes) {
  // JerkPlan::extremal (the family's members and releases, solved for the duration) against
  // the brute force's most eager motion switched by bisection: the same least and most
  // ground for 20,000 random joints at random durations from the fastest velocity change on.
  testing::RandomCases cases(10);
  std::mt19937_64 rng(11);
  int compared = 0;
  double worst = 0;
  for (int c = 0; c < 20000; ++c) {
    const TrajectoryInput in = cases.next(1);
    const JerkLimits limits{in.max_velocity[0], in.max_acceleration[0], in.max_jerk[0]};
    JerkPlan plan;
    plan.plan(JerkTask{in.position[0], in.velocity[0], in.acceleration[0], in.target_position[0],
                       in.target_velocity[0]},
              limits);
    const double T = plan.min_duration() * std::uniform_real_distribution<double>(0.5, 3)(rng);
    for (double direction : {1.0, -1.0}) {
      JerkPlan::Extremal e;
      const testing::Limits1 l{limits.velocity, limits.acceleration, limits.jerk};
      double reference = 0;
      const bool ours = plan.extremal(T, direction, e);
      const bool theirs = testing::most_ground(direction * in.velocity[0],
                                               direction * in.acceleration[0],
                                               direction * in.target_velocity[0], l, T, reference);
      reference *= direction;
      const double scale = limits.velocity * (T + limits.acceleration / limits.jerk);
      if (ours != theirs) {
        // Only at the shortest duration itself may rounding decide differently.
        JerkPlan::Extremal shorter;
        EXPECT_FALSE(plan.extremal(T * (1 - 1e-9), direction, shorter) &&
                     plan.extremal(T * (1 + 1e-9), direction, shorter))
            << testing::describe(in) << "\nT " << T;
        continue;
      }
      if (!ours) continue;
      ++compared;
      double total = 0;
      for (int k = 0; k < e.count; ++k) total += e.durations[k];
      EXPECT_NEAR(total, T, 1e-9 * T) << testing::describe(in);
      worst = std::max(worst, std::abs(e.displacement - reference) / scale);
      EXPECT_NEAR(e.displacement, reference, 1e-9 * scale) << testing::describe(in) << "\nT " << T;
    }
  }
  std::printf("extremal motions: %d compared, largest difference %.3g of the scale\n", compared,
              worst);
}

TEST(TrajectoryOptimality, ALongCruise) {
  // Found by the long run: 405 s at 0.067 m/s, where the brute force's Newton tolerance
  // once let it finish 1e-6 s early by ending slightly off the target.
  TrajectoryInput in;
  in.position[0] = 4.029554291485244, in.velocity[0] = 0.049577353578864128;
  in.acceleration[0] = -0.23044982991156343, in.target_position[0] = 30.837357920980459;
  in.max_velocity[0] = 0.066685431348921909, in.max_acceleration[0] = 46.768331524130474;
  in.max_jerk[0] = 0.228393076742753;
  std::mt19937_64 rng(1);
  testing::Tally tally;
  tally.add(testing::ours(in), testing::optimum(in, 0, rng), in);
  EXPECT_EQ(tally.worse + tally.better, 0);
}

}  // namespace
}  // namespace armctl::motion

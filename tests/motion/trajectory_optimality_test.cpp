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

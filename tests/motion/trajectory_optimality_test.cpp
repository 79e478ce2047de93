// Time-optimality of the trajectory generator against a brute force that knows nothing of
// its profile family (trajectory_brute_force.hpp, docs/trajectories.md "Optimality check").
#include <gtest/gtest.h>

#include "trajectory_brute_force.hpp"

namespace armctl::motion {
namespace {

TEST(TrajectoryOptimality, OneJointMatchesTheBruteForce) { testing::check_one_joint_optimality(7, 60); }

TEST(TrajectoryOptimality, TwoJointsSynchronizeAtTheSlowerOptimum) { testing::check_two_joint_optimality(8, 30); }

}  // namespace
}  // namespace armctl::motion

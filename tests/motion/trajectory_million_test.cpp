// The long run of the trajectory generator's checks (CTest label `long`, not part of
// `make test`; run with `ctest -L long`): 1,000,000 random cases checked as in
// trajectory_test, and the time-optimality checks on ten times as many cases.
#include <gtest/gtest.h>

#include "trajectory_brute_force.hpp"
#include "trajectory_random_cases.hpp"

namespace armctl::motion {
namespace {

TEST(TrajectoryLong, MillionCases) {
  testing::run_random_cases(1000003, 1000000);
}

TEST(TrajectoryLong, OneJointOptimality) {
  testing::check_one_joint_optimality(17, 1200);
}

TEST(TrajectoryLong, TwoJointOptimality) {
  testing::check_two_joint_optimality(18, 600);
}

TEST(TrajectoryLong, SynchronizedOptimality) {
  testing::check_synchronized_optimality(19, 1000000, 8);
}

}  // namespace
}  // namespace armctl::motion

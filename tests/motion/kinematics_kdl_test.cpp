// Both arms' kinematics against KDL built from the same URDF file: forward kinematics over
// random configurations, FK(IK(p)) = p over random reachable poses (every solution inside
// the limits, the configuration the pose came from among them), and the Jacobian.
// ARMCTL_KINEMATICS_SAMPLES sets the sample count (default 100000 per arm and check).
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>
#include <kdl/chainjnttojacsolver.hpp>

#include "arm_files.hpp"

namespace armctl::motion {
namespace {

using testing::position_error;
using testing::rotation_error;

std::string sci(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

int samples() {
  if (const char* s = std::getenv("ARMCTL_KINEMATICS_SAMPLES")) return std::max(1, std::atoi(s));
  return 100000;
}

class KinematicsVsKdl : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    chain = testing::shipped_chain(GetParam());
    limits = urdf_position_limits(chain);
    kinematics = testing::shipped_kinematics(GetParam());
    kdl = testing::kdl_chain(testing::urdf_text(GetParam()), "base_link", "tool");
  }
  UrdfChain chain;
  std::vector<PositionLimits> limits;
  std::unique_ptr<Kinematics> kinematics;
  KDL::Chain kdl;
};

TEST_P(KinematicsVsKdl, KdlSeesTheSameChain) {
  EXPECT_EQ(int(kdl.getNrOfJoints()), kinematics->joint_count());
  EXPECT_EQ(int(chain.joints.size()), kinematics->joint_count());
}

TEST_P(KinematicsVsKdl, ForwardAgreesWithKdl) {
  KDL::ChainFkSolverPos_recursive fk(kdl);
  testing::RandomJoints random(limits, 1);
  double worst_position = 0, worst_rotation = 0;
  for (int n = 0; n < samples(); ++n) {
    const JointVector q = random();
    KDL::Frame f;
    ASSERT_GE(fk.JntToCart(testing::to_kdl(q), f), 0);
    const Eigen::Isometry3d expected = testing::to_eigen(f);
    const Pose got = kinematics->forward(q);
    worst_position = std::max(worst_position, position_error(got.position, expected.translation()));
    worst_rotation = std::max(worst_rotation, rotation_error(got.orientation.toRotationMatrix(), expected.linear()));
  }
  EXPECT_LT(worst_position, 1e-9);
  EXPECT_LT(worst_rotation, 1e-9);
  RecordProperty("fk_worst_position_m", sci(worst_position));
  RecordProperty("fk_worst_rotation", sci(worst_rotation));
}

TEST_P(KinematicsVsKdl, InverseReachesEveryRandomReachablePose) {
  KDL::ChainFkSolverPos_recursive fk(kdl);
  testing::RandomJoints random(limits, 2);
  double worst_position = 0, worst_rotation = 0;
  int failures = 0, missing_original = 0;
  std::size_t total_solutions = 0;
  for (int n = 0; n < samples(); ++n) {
    const JointVector q = random();
    const JointVector near = random();
    // The pose comes from KDL, so that the analytic IK is checked against the oracle's FK.
    KDL::Frame f;
    ASSERT_GE(fk.JntToCart(testing::to_kdl(q), f), 0);
    const Eigen::Isometry3d t = testing::to_eigen(f);
    IkRequest request{Pose{t.translation(), Eigen::Quaterniond(t.linear())}};
    auto solutions = kinematics->inverse(request, near);
    if (!solutions) {
      if (++failures <= 3) ADD_FAILURE() << "no IK for " << q.transpose() << ": " << solutions.error().message;
      continue;
    }
    bool found = false;
    total_solutions += solutions->size();
    for (const auto& s : *solutions) {
      for (int i = 0; i < q.size(); ++i) {
        ASSERT_GE(s.joints[i], limits[std::size_t(i)].lower) << i;
        ASSERT_LE(s.joints[i], limits[std::size_t(i)].upper) << i;
      }
      KDL::Frame g;
      ASSERT_GE(fk.JntToCart(testing::to_kdl(s.joints), g), 0);
      const Eigen::Isometry3d back = testing::to_eigen(g);
      worst_position = std::max(worst_position, position_error(back.translation(), t.translation()));
      worst_rotation = std::max(worst_rotation, rotation_error(back.linear(), t.linear()));
      if ((s.joints - q).cwiseAbs().maxCoeff() < 1e-6) found = true;
    }
    if (!found && ++missing_original <= 3) {
      ADD_FAILURE() << "the joints the pose came from are not among the " << solutions->size()
                    << " solutions: " << q.transpose();
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(missing_original, 0);
  EXPECT_LT(worst_position, 1e-9);
  EXPECT_LT(worst_rotation, 1e-9);
  RecordProperty("ik_worst_position_m", sci(worst_position));
  RecordProperty("ik_worst_rotation", sci(worst_rotation));
  RecordProperty("solutions_per_pose", sci(double(total_solutions) / samples()));
}

TEST_P(KinematicsVsKdl, SolutionsAreSortedNearestFirst) {
  testing::RandomJoints random(limits, 3);
  for (int n = 0; n < 2000; ++n) {
    const JointVector q = random();
    auto solutions = kinematics->inverse(IkRequest{kinematics->forward(q)}, q);
    ASSERT_TRUE(solutions.ok()) << solutions.error().message;
    // Asked near the joints it came from, the first solution is those joints.
    EXPECT_LT(((*solutions)[0].joints - q).cwiseAbs().maxCoeff(), 1e-6) << q.transpose();
    double last = 0;
    for (const auto& s : *solutions) {
      const double d = (s.joints - q).squaredNorm();
      EXPECT_GE(d, last - 1e-12);
      last = d;
    }
  }
}

TEST_P(KinematicsVsKdl, JacobianAgreesWithKdl) {
  KDL::ChainJntToJacSolver solver(kdl);
  testing::RandomJoints random(limits, 4);
  double worst = 0;
  for (int n = 0; n < 10000; ++n) {
    const JointVector q = random();
    KDL::Jacobian expected(kdl.getNrOfJoints());
    ASSERT_GE(solver.JntToJac(testing::to_kdl(q), expected), 0);
    const Jacobian got = kinematics->jacobian(q);
    ASSERT_EQ(got.cols(), q.size());
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < q.size(); ++c) worst = std::max(worst, std::abs(got(r, c) - expected(unsigned(r), unsigned(c))));
    }
  }
  EXPECT_LT(worst, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Arms, KinematicsVsKdl, ::testing::Values("scara", "xarm"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace
}  // namespace armctl::motion

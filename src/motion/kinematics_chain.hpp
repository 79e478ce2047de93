// What both kinematic families share: the chain as a product of joint motions (forward
// kinematics, the geometric Jacobian, the joints' axes at zero), the small geometric
// subproblems their analytic IK is made of, and the checks and ordering of solutions.
// Internal to src/motion (the families' .cpp files).
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "motion/kinematics.hpp"
#include "motion/urdf_chain.hpp"

namespace armctl::motion::detail {

// Lengths and angles below these count as zero when checking a chain's shape: a URDF
// written with 16 significant digits meets them; one that is off by more is another shape.
inline constexpr double kShapeTolerance = 1e-9;

class ChainModel {
 public:
  explicit ChainModel(const UrdfChain& chain);
  int size() const { return n_; }
  const std::string& name(int i) const { return names_[std::size_t(i)]; }
  bool revolute(int i) const { return joints_[std::size_t(i)].revolute; }
  Eigen::Isometry3d forward(const JointVector& q) const;
  Jacobian jacobian(const JointVector& q) const;
  // At zero, in the base frame: joint i's unit axis and a point on it; the tool frame.
  const Eigen::Vector3d& axis0(int i) const { return axis0_[std::size_t(i)]; }
  const Eigen::Vector3d& point0(int i) const { return point0_[std::size_t(i)]; }
  const Eigen::Isometry3d& tool0() const { return tool0_; }

 private:
  struct Joint {
    Eigen::Isometry3d from_previous = Eigen::Isometry3d::Identity();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
    bool revolute = true;
  };
  Eigen::Isometry3d motion(int i, double q) const;
  int n_ = 0;
  std::array<Joint, kMaxChainJoints> joints_{};
  std::array<std::string, kMaxChainJoints> names_{};
  std::array<Eigen::Vector3d, kMaxChainJoints> axis0_{}, point0_{};
  Eigen::Isometry3d tip_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d tool0_ = Eigen::Isometry3d::Identity();
};

// Angle of the rotation about unit axis w that takes x's component across w onto y's
// (Paden-Kahan subproblem 1). 0 when either has no such component.
double rotation_angle(const Eigen::Vector3d& w, const Eigen::Vector3d& x, const Eigen::Vector3d& y);

// Distance of point p from the line through a with unit direction w.
double distance_to_line(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& w);

// A planar two-link arm: link vectors l1 (first joint to second) and l2 (second joint to the
// end) at zero, both joints turning counter-clockwise for positive angles. Solutions for the
// end at d (relative to the first joint): angles (a1, a2), none when out of reach.
struct Planar2R {
  Eigen::Vector2d l1, l2;
  double length1() const { return l1.norm(); }
  double length2() const { return l2.norm(); }
  struct Solution {
    double a1, a2;
    Eigen::Vector2d elbow;  // the second joint's position, relative to the first
  };
  // 0, 1 (stretched or folded) or 2 solutions; `shortfall` says by how much d is out of
  // reach: > 0 beyond the outer radius, < 0 inside the inner one (metres), else 0.
  int solve(const Eigen::Vector2d& d, std::array<Solution, 2>& out, double& shortfall) const;
  // sin of the angle between the two links at second-joint angle a2: 0 stretched or folded.
  double bend_sine(double a2) const;
};

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
Eigen::Vector2d rotate2(const Eigen::Vector2d& v, double angle);

// A joint value for people: degrees for revolute joints, millimetres for prismatic ones.
std::string joint_value_text(bool revolute, double value);

// Brings revolute joint values within their limits by whole turns (the turn nearest `near`
// when several fit), clamps values within a rounding error of a limit, and says which joint
// is outside and by how much when one is. Empty string = inside.
std::string fit_into_limits(const ChainModel& chain, std::span<const PositionLimits> limits,
                            const JointVector& near, JointVector& q);

// The request's target with a unit quaternion, or why it cannot be one.
Result<Pose> checked_target(const Pose& target);
Status check_near(const ChainModel& chain, const JointVector& near);
// Checks the limits' count and values against the chain.
Status check_limits(const ChainModel& chain, std::span<const PositionLimits> limits, const char* family);

// Sorts nearest to `near` first (revolute in rad, prismatic in m x 10, squared sum) and drops
// solutions that repeat an earlier one.
void sort_and_dedupe(const ChainModel& chain, const JointVector& near, std::vector<IkSolution>& solutions);

Error unreachable(std::string message);

}  // namespace armctl::motion::detail

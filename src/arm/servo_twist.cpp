#include "arm/servo_twist.hpp"

#include <Eigen/Cholesky>
#include <Eigen/SVD>

namespace armctl::arm {
namespace {

constexpr int kMax = motion::kMaxChainJoints;
using Rows3 = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMax>;
using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;
using Inverse = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMax, 3>;

// Damping of a least-squares solve, per singular value s (Nakamura's rule): the floor, plus up
// to `most` as s falls below `near`. Far from a singularity the floor is negligible beside
// s^2; at one, the damping bounds s / (s^2 + damping).
struct Damping {
  double floor, near, most;
  double at(double s) const { return floor + (s < near ? most * (1 - (s / near) * (s / near)) : 0.0); }
};
// Position rows: tenths of a metre per radian far from a singularity.
constexpr Damping kPositionDamping{1e-6, 0.02, 1e-4};  // m^2, m, m^2
// Rotation rows: about one far from a singularity, zero in a direction the arm cannot turn.
constexpr Damping kRotationDamping{1e-4, 0.3, 0.05};

// V diag(s / (s^2 + damping(s))) U^T: the damped inverse of a 3-row matrix.
Inverse damped_inverse(const Rows3& a, const Damping& damping) {
  Eigen::JacobiSVD<Rows3> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto& s = svd.singularValues();
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1> gain(s.size());
  for (int k = 0; k < s.size(); ++k) gain[k] = s[k] / (s[k] * s[k] + damping.at(s[k]));
  return svd.matrixV() * gain.asDiagonal() * svd.matrixU().transpose();
}

}  // namespace

motion::Jacobian tool_jacobian(const ArmKinematics& kinematics, const motion::JointVector& chain) {
  const motion::Kinematics& k = *kinematics.model().kinematics;
  motion::Jacobian j = k.jacobian(chain);
  // The chain's Jacobian is of its last link's origin; the tool point hangs `r` from it and
  // moves as well with every rotation: v_tool = v + w x r.
  const Eigen::Vector3d r = kinematics.forward(chain).position - k.forward(chain).position;
  for (int c = 0; c < j.cols(); ++c) {
    const Eigen::Vector3d w = j.block<3, 1>(3, c);
    j.block<3, 1>(0, c) += w.cross(r);
  }
  return j;
}

double position_condition(const motion::Jacobian& jacobian) {
  const Rows3 p = jacobian.topRows<3>();
  Eigen::JacobiSVD<Rows3> svd(p);
  const auto& s = svd.singularValues();
  if (s.size() < 3 || s(2) <= 0) return std::numeric_limits<double>::infinity();
  return s(0) / s(2);
}

motion::JointVector joint_velocities_for(const motion::Jacobian& jacobian, const Eigen::Vector3d& linear,
                                         const Eigen::Vector3d& angular) {
  const Rows3 jp = jacobian.topRows<3>(), jo = jacobian.bottomRows<3>();
  const Inverse jp_inv = damped_inverse(jp, kPositionDamping);
  motion::JointVector q = jp_inv * linear;
  // The rotation with what the position leaves free: in the null space of the position rows.
  Square null = Square::Identity(jacobian.cols(), jacobian.cols()) - jp_inv * jp;
  const Rows3 jo_null = jo * null;
  const Eigen::Vector3d rest = angular - jo * q;
  q += null * (damped_inverse(jo_null, kRotationDamping) * rest);
  return q;
}

}  // namespace armctl::arm

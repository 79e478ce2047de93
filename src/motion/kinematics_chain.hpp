// What both kinematic families share: the chain as a product of joint motions (forward
// kinematics, the geometric Jacobian, the joints' axes at zero), the small geometric
// subproblems their analytic IK is made of, and the checks and ordering of solutions.
// Internal to src/motion (the families' .cpp files).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
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
  // Joint i's frame after its motion, relative to the previous joint's: rotation
  // A + s B + (1 - c) C for a revolute joint (Rodrigues, folded into the fixed rotation A
  // once), translation `offset` (+ q `slide` for a prismatic joint).
  struct Joint {
    Eigen::Matrix3d a = Eigen::Matrix3d::Identity(), b = Eigen::Matrix3d::Zero(), c = Eigen::Matrix3d::Zero();
    Eigen::Vector3d offset = Eigen::Vector3d::Zero(), slide = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // in the joint's own frame
    bool revolute = true;
  };
  // Runs `visit(i, rotation, position)` with joint i's frame before its motion (its axis is
  // rotation * axis), and returns the tool frame's rotation and position.
  template <typename Visit>
  void walk(const JointVector& q, Eigen::Matrix3d& r, Eigen::Vector3d& p, Visit&& visit) const;
  int n_ = 0;
  std::array<Joint, kMaxChainJoints> joints_{};
  std::array<std::string, kMaxChainJoints> names_{};
  std::array<Eigen::Vector3d, kMaxChainJoints> axis0_{}, point0_{};
  Eigen::Matrix3d tip_rotation_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d tip_offset_ = Eigen::Vector3d::Zero();
  Eigen::Isometry3d tool0_ = Eigen::Isometry3d::Identity();
};

// What both analytic families share: forward kinematics and the Jacobian straight from the
// chain, the joint count checked on every call, the chain joints' limits.
class ChainKinematics : public Kinematics {
 public:
  ChainKinematics(ChainModel chain, std::span<const PositionLimits> limits)
      : chain_(std::move(chain)), limits_(limits.begin(), limits.end()) {}
  int joint_count() const override { return chain_.size(); }
  Pose forward(const JointVector& joints) const override {
    check_size(joints);
    const Eigen::Isometry3d t = chain_.forward(joints);
    return Pose{t.translation(), Eigen::Quaterniond(t.linear())};
  }
  Jacobian jacobian(const JointVector& joints) const override {
    check_size(joints);
    return chain_.jacobian(joints);
  }

 protected:
  // Throws ArmctlError(invalid_argument): a caller's bug, not outside input.
  void check_size(const JointVector& joints) const;

  ChainModel chain_;
  std::vector<PositionLimits> limits_;
};

// An angle with its cosine and sine (the solvers pass these on instead of calling sin/cos).
struct Turn {
  double angle = 0, c = 1, s = 0;
  Turn operator+(const Turn& o) const { return {angle + o.angle, c * o.c - s * o.s, s * o.c + c * o.s}; }
  Turn operator-() const { return {-angle, c, -s}; }
  Turn half_turn() const;  // this + pi
};
Turn turn_of(double angle);

// The rotation about unit axis w that takes x's component across w onto y's (Paden-Kahan
// subproblem 1). Zero when either has no such component.
inline Turn rotation_turn(const Eigen::Vector3d& w, const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  const Eigen::Vector3d xp = x - w * w.dot(x);
  const Eigen::Vector3d yp = y - w * w.dot(y);
  const double s = w.dot(xp.cross(yp)), c = xp.dot(yp);
  const double h = std::sqrt(c * c + s * s);  // values near 1: no overflow for hypot to guard
  if (!(h > 0)) return Turn{};
  return Turn{std::atan2(s, c), c / h, s / h};
}
inline double rotation_angle(const Eigen::Vector3d& w, const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  return rotation_turn(w, x, y).angle;
}
// v turned by `t` about unit axis w (Rodrigues).
inline Eigen::Vector3d rotated(const Eigen::Vector3d& w, const Turn& t, const Eigen::Vector3d& v) {
  return t.c * v + t.s * w.cross(v) + (1 - t.c) * w.dot(v) * w;
}
// The rotation matrix of `t` about unit axis w (Rodrigues).
inline Eigen::Matrix3d rotation(const Eigen::Vector3d& w, const Turn& t) {
  // I + s K + (1 - c) K^2, with K^2 = w w^T - I.
  const double v = 1 - t.c;
  Eigen::Matrix3d m;
  m << t.c + v * w.x() * w.x(), v * w.x() * w.y() - t.s * w.z(), v * w.x() * w.z() + t.s * w.y(),
      v * w.y() * w.x() + t.s * w.z(), t.c + v * w.y() * w.y(), v * w.y() * w.z() - t.s * w.x(),
      v * w.z() * w.x() - t.s * w.y(), v * w.z() * w.y() + t.s * w.x(), t.c + v * w.z() * w.z();
  return m;
}

// Distance of point p from the line through a with unit direction w.
double distance_to_line(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& w);

// A planar two-link arm: link vectors l1 (first joint to second) and l2 (second joint to the
// end) at zero, both joints turning counter-clockwise for positive angles. Solutions for the
// end at d (relative to the first joint): angles (a1, a2), none when out of reach.
struct Planar2R {
  Planar2R() = default;
  Planar2R(const Eigen::Vector2d& link1, const Eigen::Vector2d& link2);
  Eigen::Vector2d l1 = Eigen::Vector2d::UnitX(), l2 = Eigen::Vector2d::UnitX();
  double length1() const { return L1; }
  double length2() const { return L2; }
  struct Solution {
    Turn a1, a2;
    Eigen::Vector2d elbow;  // the second joint's position, relative to the first
  };
  // 0, 1 (stretched or folded) or 2 solutions; `shortfall` says by how much d is out of
  // reach: > 0 beyond the outer radius, < 0 inside the inner one (metres), else 0.
  int solve(const Eigen::Vector2d& d, std::array<Solution, 2>& out, double& shortfall) const;
  // sin of the angle between the two links at second-joint angle a2: 0 stretched or folded.
  double bend_sine(double a2) const;

 private:
  double L1 = 1, L2 = 1;
  Turn beta;  // l2's angle from l1
};

inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
Eigen::Vector2d rotate2(const Eigen::Vector2d& v, double angle);
inline Eigen::Vector2d rotate2(const Eigen::Vector2d& v, const Turn& t) {
  return {t.c * v.x() - t.s * v.y(), t.s * v.x() + t.c * v.y()};
}

// A joint value for people: degrees for revolute joints, millimetres for prismatic ones.
std::string joint_value_text(bool revolute, double value);

// Brings revolute joint values within their limits by whole turns (the turn nearest `near`
// when several fit) and clamps values within a rounding error of a limit. Returns the
// first joint that stays outside (-1: none); `limit_miss_text` says it for people.
int fit_into_limits(const ChainModel& chain, std::span<const PositionLimits> limits, const JointVector& near,
                    JointVector& q);
// The same for joint i alone (false: outside), so that a branch can stop early.
inline bool fit_joint(const ChainModel& chain, std::span<const PositionLimits> limits, const JointVector& near, int i,
               double& value) {
  constexpr double kRounding = 1e-9;  // rad or m: a value this close to a limit is at it
  const PositionLimits& l = limits[std::size_t(i)];
  double v = value;
  if (chain.revolute(i)) {
    // The turn of v nearest `near`, then the nearest turn that fits if that one does not.
    if (std::abs(near[i] - v) > std::numbers::pi) v += 2 * std::numbers::pi * std::round((near[i] - v) / (2 * std::numbers::pi));
    if (v > l.upper + kRounding) v -= 2 * std::numbers::pi * std::ceil((v - l.upper - kRounding) / (2 * std::numbers::pi));
    if (v < l.lower - kRounding) v += 2 * std::numbers::pi * std::ceil((l.lower - kRounding - v) / (2 * std::numbers::pi));
  }
  if (v > l.upper + kRounding || v < l.lower - kRounding) return false;
  value = std::clamp(v, l.lower, l.upper);
  return true;
}
std::string limit_miss_text(const ChainModel& chain, std::span<const PositionLimits> limits, int joint,
                            double value);

// A branch the limits refused: kept as numbers, put in words only when nothing was found.
struct Refusal {
  std::optional<Elbow> elbow;
  std::string_view branch;  // the rest of the configuration: "wrist flipped" (static text)
  int joint;
  double value;
};

// The request's target with a unit quaternion, or why it cannot be one.
Result<Pose> checked_target(const Pose& target);
Status check_near(const ChainModel& chain, const JointVector& near);
// Checks the limits' count and values against the chain.
Status check_limits(const ChainModel& chain, std::span<const PositionLimits> limits, const char* family);

// Sorts nearest to `near` first (revolute in rad, prismatic in m x 10, squared sum) and drops
// solutions that repeat an earlier one.
void sort_and_dedupe(const ChainModel& chain, const JointVector& near, std::vector<IkSolution>& solutions);

Error unreachable(std::string message);
Error limits_refused(const ChainModel& chain, std::span<const PositionLimits> limits,
                     std::span<const Refusal> refusals);

}  // namespace armctl::motion::detail

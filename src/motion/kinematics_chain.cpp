#include "motion/kinematics_chain.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace armctl::motion::detail {

namespace {
constexpr double kPi = std::numbers::pi;
}

ChainModel::ChainModel(const UrdfChain& chain) {
  n_ = int(std::min<std::size_t>(chain.joints.size(), kMaxChainJoints));
  for (int i = 0; i < n_; ++i) {
    const auto& j = chain.joints[std::size_t(i)];
    joints_[std::size_t(i)] = Joint{j.from_previous, j.axis.normalized(), j.type == ChainJointType::revolute};
    names_[std::size_t(i)] = j.name;
  }
  tip_ = chain.tip_from_last;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < n_; ++i) {
    t = t * joints_[std::size_t(i)].from_previous;
    axis0_[std::size_t(i)] = t.linear() * joints_[std::size_t(i)].axis;
    point0_[std::size_t(i)] = t.translation();
  }
  tool0_ = t * tip_;
}

Eigen::Isometry3d ChainModel::motion(int i, double q) const {
  const Joint& j = joints_[std::size_t(i)];
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  if (j.revolute) {
    m.linear() = Eigen::AngleAxisd(q, j.axis).toRotationMatrix();
  } else {
    m.translation() = q * j.axis;
  }
  return m;
}

Eigen::Isometry3d ChainModel::forward(const JointVector& q) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < n_; ++i) t = t * joints_[std::size_t(i)].from_previous * motion(i, q[i]);
  return t * tip_;
}

Jacobian ChainModel::jacobian(const JointVector& q) const {
  std::array<Eigen::Vector3d, kMaxChainJoints> axes, points;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < n_; ++i) {
    t = t * joints_[std::size_t(i)].from_previous;
    axes[std::size_t(i)] = t.linear() * joints_[std::size_t(i)].axis;
    points[std::size_t(i)] = t.translation();
    t = t * motion(i, q[i]);
  }
  const Eigen::Vector3d tool = (t * tip_).translation();
  Jacobian jac(6, n_);
  for (int i = 0; i < n_; ++i) {
    const Eigen::Vector3d& w = axes[std::size_t(i)];
    if (joints_[std::size_t(i)].revolute) {
      jac.col(i) << w.cross(tool - points[std::size_t(i)]), w;
    } else {
      jac.col(i) << w, Eigen::Vector3d::Zero();
    }
  }
  return jac;
}

double rotation_angle(const Eigen::Vector3d& w, const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  const Eigen::Vector3d xp = x - w * w.dot(x);
  const Eigen::Vector3d yp = y - w * w.dot(y);
  return std::atan2(w.dot(xp.cross(yp)), xp.dot(yp));
}

double distance_to_line(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& w) {
  return (p - a).cross(w).norm();
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

Eigen::Vector2d rotate2(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

int Planar2R::solve(const Eigen::Vector2d& d, std::array<Solution, 2>& out, double& shortfall) const {
  const double L1 = length1(), L2 = length2();
  const double r = d.norm();
  shortfall = 0;
  // Reach tolerance: a rounding error of the lengths, not a real miss.
  const double slack = 1e-12 * (L1 + L2);
  if (r > L1 + L2 + slack) {
    shortfall = r - (L1 + L2);
    return 0;
  }
  if (r < std::abs(L1 - L2) - slack) {
    shortfall = r - std::abs(L1 - L2);
    return 0;
  }
  const double beta = std::atan2(cross2(l1, l2), l1.dot(l2));  // l2's angle from l1 at zero
  const double c = std::clamp((r * r - L1 * L1 - L2 * L2) / (2 * L1 * L2), -1.0, 1.0);
  double g = std::acos(c);  // the links' relative angle, this branch
  // Stretched or folded: acos turns a rounding error of c into an angle of ~1e-8 rad, two
  // solutions that are one. Snapping to the singular angle moves the end by about
  // L1 L2 g^2 / (2 r) (second order): snap while that stays below a picometre.
  const double snap = 1e-12 * 2 * std::max(r, 1e-300) / (L1 * L2);
  if (g * g < snap) g = 0;
  if ((kPi - g) * (kPi - g) < snap) g = kPi;
  const int count = (g == 0 || g == kPi) ? 1 : 2;
  for (int k = 0; k < count; ++k) {
    const double rel = k == 0 ? g : -g;
    const double a2 = rel - beta;
    const Eigen::Vector2d v = l1 + rotate2(l2, a2);
    const double a1 = std::atan2(cross2(v, d), v.dot(d));
    out[std::size_t(k)] = Solution{a1, a2, rotate2(l1, a1)};
  }
  return count;
}

double Planar2R::bend_sine(double a2) const {
  return cross2(l1, rotate2(l2, a2)) / (length1() * length2());
}

std::string joint_value_text(bool revolute, double value) {
  if (revolute) return fmt::format("{:.1f} deg", value * 180 / kPi);
  return fmt::format("{:.1f} mm", value * 1000);
}

namespace {
std::string limits_text(bool revolute, const PositionLimits& l) {
  if (revolute) return fmt::format("{:.1f}..{:.1f} deg", l.lower * 180 / kPi, l.upper * 180 / kPi);
  return fmt::format("{:.1f}..{:.1f} mm", l.lower * 1000, l.upper * 1000);
}
}  // namespace

std::string fit_into_limits(const ChainModel& chain, std::span<const PositionLimits> limits,
                            const JointVector& near, JointVector& q) {
  constexpr double kRounding = 1e-9;  // rad or m: a value this close to a limit is at it
  for (int i = 0; i < chain.size(); ++i) {
    const PositionLimits& l = limits[std::size_t(i)];
    double v = q[i];
    if (chain.revolute(i)) {
      // The turn of v nearest `near`, then the nearest turn that fits if that one does not.
      v += 2 * kPi * std::round((near[i] - v) / (2 * kPi));
      if (v > l.upper + kRounding) v -= 2 * kPi * std::ceil((v - l.upper - kRounding) / (2 * kPi));
      if (v < l.lower - kRounding) v += 2 * kPi * std::ceil((l.lower - kRounding - v) / (2 * kPi));
    }
    if (v > l.upper + kRounding || v < l.lower - kRounding) {
      // Report the turn nearest the limits' middle (the value people expect to see).
      double shown = q[i];
      if (chain.revolute(i)) shown = std::remainder(q[i] - 0.5 * (l.lower + l.upper), 2 * kPi) + 0.5 * (l.lower + l.upper);
      return fmt::format("joint {} would be {}, outside {}", chain.name(i),
                         joint_value_text(chain.revolute(i), shown), limits_text(chain.revolute(i), l));
    }
    q[i] = std::clamp(v, l.lower, l.upper);
  }
  return {};
}

Result<Pose> checked_target(const Pose& target) {
  const auto& p = target.position;
  const auto& q = target.orientation;
  if (!p.allFinite() || !q.coeffs().allFinite()) {
    return Error{ErrorKind::invalid_argument, "target pose is not finite (NaN or infinite position or orientation)"};
  }
  if (p.norm() > 1000) {
    return Error{ErrorKind::invalid_argument, fmt::format("target position {:.1f} m from the base is not a position "
                                                          "for an arm (at most 1000 m allowed)", p.norm())};
  }
  const double norm = q.norm();
  if (std::abs(norm - 1) > 1e-6) {
    return Error{ErrorKind::invalid_argument,
                 fmt::format("target orientation quaternion has norm {:.9g}; it must be a unit quaternion", norm)};
  }
  Pose out = target;
  out.orientation.normalize();
  return out;
}

Status check_near(const ChainModel& chain, const JointVector& near) {
  if (near.size() != chain.size()) {
    return Error{ErrorKind::invalid_argument,
                 fmt::format("{} joint values given as the current position; the chain has {} joints", near.size(),
                             chain.size())};
  }
  if (!near.allFinite()) return Error{ErrorKind::invalid_argument, "current joint values are not finite"};
  return Ok{};
}

Status check_limits(const ChainModel& chain, std::span<const PositionLimits> limits, const char* family) {
  if (int(limits.size()) != chain.size()) {
    return Error{ErrorKind::invalid_config, fmt::format("{} limits given for the {} chain of {} joints",
                                                        limits.size(), family, chain.size())};
  }
  for (int i = 0; i < chain.size(); ++i) {
    const auto& l = limits[std::size_t(i)];
    if (!std::isfinite(l.lower) || !std::isfinite(l.upper) || !(l.lower < l.upper)) {
      return Error{ErrorKind::invalid_config,
                   fmt::format("joint {}: position limits {}..{} must be finite with lower < upper", chain.name(i),
                               l.lower, l.upper)};
    }
  }
  return Ok{};
}

void sort_and_dedupe(const ChainModel& chain, const JointVector& near, std::vector<IkSolution>& solutions) {
  auto distance = [&](const JointVector& q) {
    double sum = 0;
    for (int i = 0; i < chain.size(); ++i) {
      const double d = (q[i] - near[i]) * (chain.revolute(i) ? 1.0 : 10.0);
      sum += d * d;
    }
    return sum;
  };
  std::stable_sort(solutions.begin(), solutions.end(),
                   [&](const IkSolution& a, const IkSolution& b) { return distance(a.joints) < distance(b.joints); });
  std::vector<IkSolution> kept;
  kept.reserve(solutions.size());
  for (auto& s : solutions) {
    const bool repeat = std::any_of(kept.begin(), kept.end(), [&](const IkSolution& k) {
      return (k.joints - s.joints).cwiseAbs().maxCoeff() < 1e-9;
    });
    if (!repeat) kept.push_back(std::move(s));
  }
  solutions = std::move(kept);
}

Error unreachable(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

}  // namespace armctl::motion::detail

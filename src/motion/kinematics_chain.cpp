#include "motion/kinematics_chain.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace armctl::motion::detail {

namespace {
constexpr double kPi = std::numbers::pi;
}

namespace {
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& w) {
  Eigen::Matrix3d k;
  k << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return k;
}
}  // namespace

ChainModel::ChainModel(const UrdfChain& chain) {
  n_ = int(std::min<std::size_t>(chain.joints.size(), kMaxChainJoints));
  for (int i = 0; i < n_; ++i) {
    const auto& j = chain.joints[std::size_t(i)];
    Joint& m = joints_[std::size_t(i)];
    m.axis = j.axis.normalized();
    m.revolute = j.type == ChainJointType::revolute;
    m.a = j.from_previous.linear();
    m.offset = j.from_previous.translation();
    if (m.revolute) {
      const Eigen::Matrix3d k = cross_matrix(m.axis);
      m.b = m.a * k;
      m.c = m.a * (k * k);
    } else {
      m.slide = m.a * m.axis;
    }
    names_[std::size_t(i)] = j.name;
  }
  tip_rotation_ = chain.tip_from_last.linear();
  tip_offset_ = chain.tip_from_last.translation();
  Eigen::Matrix3d r;
  Eigen::Vector3d p;
  walk(JointVector::Zero(n_), r, p, [&](int i, const Eigen::Matrix3d& ri, const Eigen::Vector3d& pi) {
    axis0_[std::size_t(i)] = ri * joints_[std::size_t(i)].axis;
    point0_[std::size_t(i)] = pi;
  });
  tool0_.linear() = r;
  tool0_.translation() = p;
}

template <typename Visit>
void ChainModel::walk(const JointVector& q, Eigen::Matrix3d& r, Eigen::Vector3d& p, Visit&& visit) const {
  r.setIdentity();
  p.setZero();
  for (int i = 0; i < n_; ++i) {
    const Joint& j = joints_[std::size_t(i)];
    p += r * j.offset;
    visit(i, r * j.a, p);
    if (j.revolute) {
      const double c = std::cos(q[i]), s = std::sin(q[i]);
      r = r * (j.a + s * j.b + (1 - c) * j.c);
    } else {
      p += r * (q[i] * j.slide);
      r = r * j.a;
    }
  }
  p += r * tip_offset_;
  r = r * tip_rotation_;
}

Eigen::Isometry3d ChainModel::forward(const JointVector& q) const {
  Eigen::Matrix3d r;
  Eigen::Vector3d p;
  walk(q, r, p, [](int, const Eigen::Matrix3d&, const Eigen::Vector3d&) {});
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  t.translation() = p;
  return t;
}

Jacobian ChainModel::jacobian(const JointVector& q) const {
  std::array<Eigen::Vector3d, kMaxChainJoints> axes, points;
  Eigen::Matrix3d r;
  Eigen::Vector3d tool;
  walk(q, r, tool, [&](int i, const Eigen::Matrix3d& ri, const Eigen::Vector3d& pi) {
    axes[std::size_t(i)] = ri * joints_[std::size_t(i)].axis;
    points[std::size_t(i)] = pi;
  });
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

Turn Turn::half_turn() const { return {angle + kPi, -c, -s}; }

Turn turn_of(double angle) { return {angle, std::cos(angle), std::sin(angle)}; }

double distance_to_line(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& w) {
  return (p - a).cross(w).norm();
}

Eigen::Vector2d rotate2(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

Planar2R::Planar2R(const Eigen::Vector2d& link1, const Eigen::Vector2d& link2)
    : l1(link1), l2(link2), L1(link1.norm()), L2(link2.norm()) {
  const double c = l1.dot(l2), s = cross2(l1, l2), h = std::hypot(c, s);
  beta = h > 0 ? Turn{std::atan2(s, c), c / h, s / h} : Turn{};
}

int Planar2R::solve(const Eigen::Vector2d& d, std::array<Solution, 2>& out, double& shortfall) const {
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
  double c = std::clamp((r * r - L1 * L1 - L2 * L2) / (2 * L1 * L2), -1.0, 1.0);
  double g = std::acos(c);  // the links' relative angle, this branch
  // Stretched or folded: acos turns a rounding error of c into an angle of ~1e-8 rad, two
  // solutions that are one. Snapping to the singular angle moves the end by about
  // L1 L2 g^2 / (2 r) (second order): snap while that stays below a picometre.
  const double snap = 1e-12 * 2 * std::max(r, 1e-300) / (L1 * L2);
  if (g * g < snap) g = 0, c = 1;
  if ((kPi - g) * (kPi - g) < snap) g = kPi, c = -1;
  const double sg = std::sqrt(std::max(0.0, 1 - c * c));
  const int count = (g == 0 || g == kPi) ? 1 : 2;
  for (int k = 0; k < count; ++k) {
    const Turn rel{k == 0 ? g : -g, c, k == 0 ? sg : -sg};
    const Turn a2 = rel + -beta;
    const Eigen::Vector2d v = l1 + rotate2(l2, a2);
    const double ca = v.dot(d), sa = cross2(v, d), h = std::sqrt(ca * ca + sa * sa);
    const Turn a1 = h > 0 ? Turn{std::atan2(sa, ca), ca / h, sa / h} : Turn{};
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

int fit_into_limits(const ChainModel& chain, std::span<const PositionLimits> limits, const JointVector& near,
                    JointVector& q) {
  for (int i = 0; i < chain.size(); ++i) {
    if (!fit_joint(chain, limits, near, i, q[i])) return i;
  }
  return -1;
}

std::string limit_miss_text(const ChainModel& chain, std::span<const PositionLimits> limits, int joint,
                            double value) {
  const PositionLimits& l = limits[std::size_t(joint)];
  const bool revolute = chain.revolute(joint);
  // The turn nearest the limits' middle (the value people expect to see).
  const double middle = 0.5 * (l.lower + l.upper);
  const double shown = revolute ? std::remainder(value - middle, 2 * kPi) + middle : value;
  return fmt::format("joint {} would be {}, outside {}", chain.name(joint), joint_value_text(revolute, shown),
                     limits_text(revolute, l));
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
  // A handful of solutions: insertion sort on distances computed once, then drop repeats.
  std::array<double, 16> d{};
  const std::size_t n = std::min(solutions.size(), d.size());
  solutions.resize(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = distance(solutions[i].joints);
  for (std::size_t i = 1; i < n; ++i) {
    for (std::size_t j = i; j > 0 && d[j] < d[j - 1]; --j) {
      std::swap(d[j], d[j - 1]);
      std::swap(solutions[j], solutions[j - 1]);
    }
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    bool repeat = false;
    for (std::size_t k = 0; k < kept && !repeat; ++k) {
      repeat = (solutions[k].joints - solutions[i].joints).cwiseAbs().maxCoeff() < 1e-9;
    }
    if (!repeat) {
      if (kept != i) solutions[kept] = std::move(solutions[i]);
      ++kept;
    }
  }
  solutions.resize(kept);
}

Error unreachable(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

Error limits_refused(const ChainModel& chain, std::span<const PositionLimits> limits,
                     std::span<const Refusal> refusals) {
  std::string all;
  for (const auto& r : refusals) {
    if (!all.empty()) all += "; ";
    const std::string elbow = r.elbow ? fmt::format("elbow {}", to_string(*r.elbow)) : std::string();
    all += fmt::format("{}{}{}: {}", elbow, elbow.empty() || r.branch.empty() ? "" : ", ", r.branch,
                       limit_miss_text(chain, limits, r.joint, r.value));
  }
  return unreachable("no solution inside the joint limits: " + all);
}

void ChainKinematics::check_size(const JointVector& joints) const {
  if (joints.size() != chain_.size()) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("{} kinematics: {} joint values given, the chain has {}", family(),
                                  joints.size(), chain_.size()));
  }
}

}  // namespace armctl::motion::detail

#include "motion/path_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <fmt/core.h>

namespace armctl::motion {

namespace {

// A path this long in samples is refused rather than checked (some 10 km of tool travel).
constexpr std::size_t kMaxSamples = 10'000'000;
// Within this of a singular configuration (bend sine, wrist axes' sine, or metres from the
// xArm's base axis) a slowed stretch is put down to the singularity.
constexpr double kNearSingularity = 0.05;
// A joint step that does not shrink below this as the step in s shrinks to kJumpWidth is a
// jump (a change of configuration), not a fast joint.
constexpr double kJumpStep = 1e-4;
constexpr double kJumpWidth = 1e-10;

Error refuse(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

Pose compose(const Pose& a, const Pose& b) {
  Pose out;
  out.position = a.position + a.orientation * b.position;
  out.orientation = (a.orientation * b.orientation).normalized();
  return out;
}

Pose inverse_of(const Pose& p) {
  Pose out;
  out.orientation = p.orientation.conjugate();
  out.position = -(out.orientation * p.position);
  return out;
}

double rotation_angle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return 2 * std::asin(std::min(1.0, (b * a.conjugate()).vec().norm()));
}

std::string shown(const PathLimits& l, double si, int per_second = 0) {
  return fmt::format("{:.1f} {}{}", to_display(l.dimension, si) + 0.0, display_unit(l.dimension),
                     per_second ? "/s" : "");
}

std::string describe(const Configuration& c) {
  std::string out;
  auto add = [&](const std::string& part) { out += (out.empty() ? "" : ", ") + part; };
  if (c.elbow) add(fmt::format("elbow {}", to_string(*c.elbow)));
  if (c.wrist_flipped) add(*c.wrist_flipped ? "wrist flipped" : "wrist not flipped");
  if (c.reaching_back) add(*c.reaching_back ? "reaching back" : "facing the point");
  return out.empty() ? "one configuration" : out;
}

bool same(const Configuration& a, const Configuration& b) {
  return a.elbow == b.elbow && a.wrist_flipped == b.wrist_flipped && a.reaching_back == b.reaching_back;
}

struct Solved {
  JointVector joints;
  Configuration configuration;
};

class Checker {
 public:
  Checker(const CartesianPath& path, const Kinematics& kinematics, const Pose& tool,
          std::span<const PathLimits> limits, bool nearest)
      : path_(path), kin_(kinematics), tool_inverse_(inverse_of(tool)), limits_(limits), nearest_(nearest) {}

  // "segment 3 (LIN): at 42 % (x 212.0 y -30.5 z 88.0 mm)"
  std::string where(double s) const {
    const int k = path_.segment_at(s);
    const Eigen::Vector3d p = path_.at(s).position * 1e3;
    return fmt::format("segment {} ({}): at {:.0f} % (x {:.1f} y {:.1f} z {:.1f} mm)", k + 1,
                       to_string(path_.segments()[std::size_t(k)].kind), path_.segment_fraction(s) * 100, p.x() + 0.0,
                       p.y() + 0.0, p.z() + 0.0);
  }

  Result<Solved> solve(double s, const JointVector& near) const {
    IkRequest request;
    request.target = compose(path_.at(s), tool_inverse_);
    request.nearest_orientation = nearest_;
    auto solutions = kin_.inverse(request, near);
    if (!solutions) return refuse(fmt::format("{}: {}", where(s), solutions.error().message));
    const IkSolution& best = solutions->front();
    return Solved{best.joints, best.configuration};
  }

  Status check_limits(double s, const JointVector& q) const {
    for (std::size_t j = 0; j < limits_.size(); ++j) {
      const PathLimits& l = limits_[j];
      const double v = q[Eigen::Index(j)];
      if (v < l.lower - 1e-9 || v > l.upper + 1e-9)
        return refuse(fmt::format("{}: joint {} would be at {}, allowed {}..{}", where(s), l.name, shown(l, v),
                                  shown(l, l.lower), shown(l, l.upper)));
    }
    return Ok{};
  }

  // Largest ds/dt the velocity limits allow for the step from qa to qb over ds, and the joint.
  std::pair<double, int> step_rate(const JointVector& qa, const JointVector& qb, double ds) const {
    double rate = std::numeric_limits<double>::infinity();
    int joint = 0;
    for (std::size_t j = 0; j < limits_.size(); ++j) {
      const double dq = std::abs(qb[Eigen::Index(j)] - qa[Eigen::Index(j)]);
      if (dq == 0) continue;
      const double r = limits_[j].velocity * ds / dq;
      if (r < rate) {
        rate = r;
        joint = int(j);
      }
    }
    return {rate, joint};
  }

  std::string singularity_note(const JointVector& q) const {
    const Singularity s = kin_.singularity(q, kNearSingularity);
    return s == Singularity::none ? "" : fmt::format(" near a singularity ({})", to_string(s));
  }

  std::string too_fast(double s, const JointVector& q, int joint, double per_s) const {
    const PathLimits& l = limits_[std::size_t(joint)];
    return fmt::format("{}: joint {} would need {} at {:.0f} % of the programmed speed, allowed {}{}", where(s), l.name,
                       shown(l, per_s * kMinPathRate, 1), kMinPathRate * 100, shown(l, l.velocity, 1),
                       singularity_note(q));
  }

  // The step a..b needs a rate below the floor: narrows it down by halves to the worst spot
  // and says whether the joints jump there (a configuration change) or only move too fast.
  Status refuse_step(double a, Solved qa, double b, Solved qb) const {
    while (b - a > kJumpWidth * std::max(1.0, path_.duration())) {
      const double m = (a + b) / 2;
      if (m <= a || m >= b) break;
      auto qm = solve(m, qa.joints);
      if (!qm) return qm.error();
      if (step_rate(qa.joints, qm->joints, m - a).first <= step_rate(qm->joints, qb.joints, b - m).first) {
        b = m;
        qb = *qm;
      } else {
        a = m;
        qa = *qm;
      }
    }
    const auto [rate, joint] = step_rate(qa.joints, qb.joints, b - a);
    const PathLimits& l = limits_[std::size_t(joint)];
    const double from = qa.joints[joint], to = qb.joints[joint];
    if (std::abs(to - from) < kJumpStep) return refuse(too_fast(a, qa.joints, joint, l.velocity / rate));
    // The continuous solution ended: at a joint limit (the kinematics keeps solutions inside
    // the limits), or at a singularity the nearest solution now lies in another configuration.
    for (std::size_t j = 0; j < limits_.size(); ++j) {
      const PathLimits& lj = limits_[j];
      const double v = qa.joints[Eigen::Index(j)];
      if (std::min(std::abs(v - lj.lower), std::abs(v - lj.upper)) < 1e-3)
        return refuse(fmt::format("{}: joint {} would leave its limits at {}, allowed {}..{}", where(a), lj.name,
                                  shown(lj, v), shown(lj, lj.lower), shown(lj, lj.upper)));
    }
    std::string change = same(qa.configuration, qb.configuration)
                             ? ""
                             : fmt::format(" ({} -> {})", describe(qa.configuration), describe(qb.configuration));
    return refuse(fmt::format("{}: the joints would jump: joint {} from {} to {}, a change of configuration{}{}; the "
                              "arm cannot follow the path through there (move around it, or split the path with a PTP)",
                              where(a), l.name, shown(l, from), shown(l, to), change, singularity_note(qa.joints)));
  }

  // Samples of the stretch [from, to] (between two rests): each segment's own step (1 mm
  // and 1 deg at its programmed rates), then halved wherever two neighbours are further apart.
  Result<std::vector<double>> grid(double from, double to) const {
    std::vector<double> s{from};
    for (const BuiltSegment& g : path_.segments()) {
      if (g.end_s <= from || g.start_s >= to) continue;
      const double t = g.end_s - g.start_s;
      double step = t;
      if (g.length > 0) step = std::min(step, kPathSampleLength * t / g.length);
      if (g.angle > 0) step = std::min(step, kPathSampleAngle * t / g.angle);
      const double n = std::ceil(t / step);
      if (n > double(kMaxSamples))
        return refuse(fmt::format("the path needs more than {} samples to check; split it", kMaxSamples));
      for (int i = 1; i <= int(n); ++i) s.push_back(i == int(n) ? g.end_s : g.start_s + t * i / n);
    }
    std::vector<double> out{s.front()};
    Pose last = path_.at(s.front());
    for (std::size_t i = 1; i < s.size(); ++i) {
      // Depth-first halving of (out.back(), s[i]].
      std::vector<std::pair<double, Pose>> pending{{s[i], path_.at(s[i])}};
      while (!pending.empty()) {
        const auto [b, pb] = pending.back();
        const double a = out.back();
        const bool far = (pb.position - last.position).norm() > kPathSampleLength ||
                         rotation_angle(last.orientation, pb.orientation) > kPathSampleAngle;
        const double m = (a + b) / 2;
        if (far && m > a && m < b) {
          pending.push_back({m, path_.at(m)});
          continue;
        }
        out.push_back(b);
        last = pb;
        pending.pop_back();
        if (out.size() > kMaxSamples)
          return refuse(fmt::format("the path needs more than {} samples to check; split it", kMaxSamples));
      }
    }
    return out;
  }

  // Derivatives by finite differences over one stretch [first, last] of the samples.
  static void differentiate(CheckedPath& c, std::size_t first, std::size_t last) {
    const std::vector<double>& s = c.s;
    const Eigen::Index n = c.joints[first].size();
    for (std::size_t i = first; i <= last; ++i) {
      c.dq_ds[i] = JointVector::Zero(n);
      c.d2q_ds2[i] = JointVector::Zero(n);
    }
    if (last == first + 1) {
      c.dq_ds[first] = c.dq_ds[last] = (c.joints[last] - c.joints[first]) / (s[last] - s[first]);
      return;
    }
    for (std::size_t i = first + 1; i < last; ++i) {
      const double h1 = s[i] - s[i - 1], h2 = s[i + 1] - s[i];
      const JointVector &q0 = c.joints[i - 1], &q1 = c.joints[i], &q2 = c.joints[i + 1];
      c.dq_ds[i] = (h1 * h1 * q2 - h2 * h2 * q0 + (h2 * h2 - h1 * h1) * q1) / (h1 * h2 * (h1 + h2));
      c.d2q_ds2[i] = 2 * (h1 * q2 - (h1 + h2) * q1 + h2 * q0) / (h1 * h2 * (h1 + h2));
    }
    const double h0 = s[first + 1] - s[first], hn = s[last] - s[last - 1];
    c.d2q_ds2[first] = c.d2q_ds2[first + 1];
    c.d2q_ds2[last] = c.d2q_ds2[last - 1];
    c.dq_ds[first] = (c.joints[first + 1] - c.joints[first]) / h0 - c.d2q_ds2[first] * h0 / 2;
    c.dq_ds[last] = (c.joints[last] - c.joints[last - 1]) / hn + c.d2q_ds2[last] * hn / 2;
  }

  Result<CheckedPath> run(const JointVector& start) {
    CheckedPath out;
    auto first = solve(0, start);
    if (!first) return first.error();
    for (std::size_t j = 0; j < limits_.size(); ++j) {
      const PathLimits& l = limits_[j];
      const double slack = l.dimension == Dimension::angle ? kStartAngleSlack : kStartLengthSlack;
      const double at = start[Eigen::Index(j)], want = first->joints[Eigen::Index(j)];
      if (std::abs(at - want) > slack)
        return refuse(fmt::format("the path does not start where the arm is: joint {} is at {}, the path's start pose "
                                  "needs {}",
                                  l.name, shown(l, at), shown(l, want)));
    }
    Solved previous = *first;
    double previous_s = 0;
    double from = 0;
    for (double rest : path_.rests()) {
      auto s = grid(from, rest);
      if (!s) return s.error();
      const std::size_t stretch_first = out.s.size();
      for (std::size_t i = 0; i < s->size(); ++i) {
        const double si = (*s)[i];
        Solved here = previous;
        if (!(i == 0 && stretch_first == 0)) {
          if (i == 0) {
            here = previous;  // the rest again, starting the next stretch
          } else {
            auto q = solve(si, previous.joints);
            if (!q) return q.error();
            here = *q;
            if (step_rate(previous.joints, here.joints, si - previous_s).first < kMinPathRate) {
              if (auto ok = refuse_step(previous_s, previous, si, here); !ok) return ok.error();
            }
          }
        }
        if (auto ok = check_limits(si, here.joints); !ok) return ok.error();
        out.s.push_back(si);
        out.joints.push_back(here.joints);
        previous = here;
        previous_s = si;
      }
      out.dq_ds.resize(out.s.size());
      out.d2q_ds2.resize(out.s.size());
      differentiate(out, stretch_first, out.s.size() - 1);
      from = rest;
    }
    return finish(std::move(out));
  }

  Result<CheckedPath> finish(CheckedPath out) const {
    out.rate_limit.resize(out.s.size());
    std::vector<int> limiting(out.s.size(), 0);
    out.max_rate = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < out.s.size(); ++i) {
      double rate = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < limits_.size(); ++j) {
        const double d = std::abs(out.dq_ds[i][Eigen::Index(j)]);
        if (d > 0 && limits_[j].velocity / d < rate) {
          rate = limits_[j].velocity / d;
          limiting[i] = int(j);
        }
      }
      out.rate_limit[i] = rate;
      out.max_rate = std::min(out.max_rate, rate);
      if (rate < kMinPathRate) {
        const int j = limiting[i];
        return refuse(too_fast(out.s[i], out.joints[i], j, std::abs(out.dq_ds[i][j])));
      }
    }
    // Stretches below full speed, each with its slowest point and the reason.
    for (std::size_t i = 0; i < out.s.size();) {
      if (out.rate_limit[i] >= 1) {
        ++i;
        continue;
      }
      std::size_t end = i, slowest = i;
      while (end < out.s.size() && out.rate_limit[end] < 1) {
        if (out.rate_limit[end] < out.rate_limit[slowest]) slowest = end;
        ++end;
      }
      SlowSpot spot;
      spot.from_s = out.s[i];
      spot.to_s = out.s[end - 1];
      spot.at_s = out.s[slowest];
      spot.segment = path_.segment_at(spot.at_s);
      spot.rate = out.rate_limit[slowest];
      spot.joint = limiting[slowest];
      spot.singularity = kin_.singularity(out.joints[slowest], kNearSingularity);
      const PathLimits& l = limits_[std::size_t(spot.joint)];
      spot.message = fmt::format("{}: slowed to {:.0f} % of the programmed speed: joint {} would need {} at full speed, "
                                 "allowed {}{}",
                                 where(spot.at_s), spot.rate * 100, l.name,
                                 shown(l, std::abs(out.dq_ds[slowest][spot.joint]), 1), shown(l, l.velocity, 1),
                                 singularity_note(out.joints[slowest]));
      out.slowed.push_back(std::move(spot));
      i = end;
    }
    return out;
  }

 private:
  const CartesianPath& path_;
  const Kinematics& kin_;
  Pose tool_inverse_;
  std::span<const PathLimits> limits_;
  bool nearest_;
};

}  // namespace

struct CheckedPath::Solver {
  CartesianPath path;
  const Kinematics* kinematics;
  Pose tool_inverse;
  bool nearest;
};

Result<CheckedPath> check_path(const CartesianPath& path, const Kinematics& kinematics, const Pose& tool,
                               const JointVector& start, std::span<const PathLimits> limits,
                               bool nearest_orientation) {
  const int n = kinematics.joint_count();
  if (path.segments().empty()) return refuse("the path has no segments");
  if (int(limits.size()) != n)
    return refuse(fmt::format("{} joint limits given for a chain of {} joints", limits.size(), n));
  if (start.size() != n) return refuse(fmt::format("{} start joints given for a chain of {} joints", start.size(), n));
  if (!start.allFinite()) return refuse("the start joints are not all finite numbers");
  if (!tool.position.allFinite() || !tool.orientation.coeffs().allFinite() ||
      std::abs(tool.orientation.norm() - 1) > 1e-6)
    return refuse("the tool frame is not a finite pose with a unit quaternion");
  for (const PathLimits& l : limits) {
    if (!(std::isfinite(l.lower) && std::isfinite(l.upper) && l.lower <= l.upper))
      return refuse(fmt::format("joint {}: position limits must be finite with lower <= upper", l.name));
    if (!(std::isfinite(l.velocity) && l.velocity > 0 && std::isfinite(l.acceleration) && l.acceleration > 0))
      return refuse(fmt::format("joint {}: velocity and acceleration limits must be finite and > 0", l.name));
  }
  Checker checker(path, kinematics, tool, limits, nearest_orientation);
  auto checked = checker.run(start);
  if (!checked) return checked;
  Pose tool_unit = tool;
  tool_unit.orientation.normalize();
  checked->solver = std::make_shared<const CheckedPath::Solver>(
      CheckedPath::Solver{path, &kinematics, inverse_of(tool_unit), nearest_orientation});
  return checked;
}

JointVector CheckedPath::joints_at(double at) const {
  if (s.empty()) return JointVector();
  if (at <= s.front()) return joints.front();
  if (at >= s.back()) return joints.back();
  // The first sample after `at`; its predecessor starts a step of positive length.
  std::size_t b = std::size_t(std::upper_bound(s.begin(), s.end(), at) - s.begin());
  std::size_t a = b - 1;
  const double h = s[b] - s[a];
  if (h <= 0) return joints[b];
  const double t = (at - s[a]) / h;
  const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
  const double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
  return h00 * joints[a] + h10 * h * dq_ds[a] + h01 * joints[b] + h11 * h * dq_ds[b];
}

JointVector CheckedPath::joints_at(double at, const JointVector& near) const {
  const JointVector interpolated = joints_at(at);
  if (!solver || solver->kinematics == nullptr) return interpolated;
  IkRequest request;
  request.target = compose(solver->path.at(at), solver->tool_inverse);
  request.nearest_orientation = solver->nearest;
  auto solutions = solver->kinematics->inverse(request, near.size() == interpolated.size() ? near : interpolated);
  if (!solutions) return interpolated;
  return solutions->front().joints;
}

}  // namespace armctl::motion

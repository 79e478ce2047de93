#include "motion/path_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <fmt/core.h>

namespace armctl::motion {

namespace {

// A path this long in samples is refused rather than checked (some 1 km of tool travel;
// the samples then take some 200 MB).
constexpr std::size_t kMaxSamples = 1'000'000;
// Within this of a singular configuration (bend sine, wrist axes' sine, or metres from the
// xArm's base axis) a slowed stretch is put down to the singularity.
constexpr double kNearSingularity = 0.05;
// A joint step that stays above its step limit as the step in s is halved down to this
// (times the path's duration) is a jump (a change of configuration), not a fast joint.
constexpr double kJumpWidth = 1e-12;

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

// The xArm's rule (docs/paths.md): its 5 joints keep the approach in the vertical plane
// through the base axis and the tool point, so each sample's orientation is turned about the
// vertical until the approach's heading is where the arm points (or half a turn from it,
// reaching back): the tool's pitch and roll stay as the path has them, only its yaw follows
// the position. An approach within 1e-9 of vertical, or a point on the base axis, fits every
// plane and is kept; the kinematics' nearest orientation absorbs what rounding leaves.
Pose facing_the_position(Pose flange) {
  const Eigen::Vector3d approach = flange.orientation * Eigen::Vector3d::UnitX();
  const double level = std::hypot(approach.x(), approach.y());
  const double radius = std::hypot(flange.position.x(), flange.position.y());
  if (level < 1e-9 || radius < 1e-9) return flange;
  const double pointing = std::atan2(flange.position.y(), flange.position.x());
  const double heading = std::atan2(approach.y(), approach.x());
  double turn = std::remainder(pointing - heading, 2 * std::numbers::pi);
  if (turn > std::numbers::pi / 2) turn -= std::numbers::pi;  // reaching back: the nearer of the two
  if (turn < -std::numbers::pi / 2) turn += std::numbers::pi;
  flange.orientation = (Eigen::Quaterniond(Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ())) * flange.orientation).normalized();
  return flange;
}

double rotation_angle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return 2 * std::asin(std::min(1.0, (b * a.conjugate()).vec().norm()));
}

std::string shown(const PathLimits& l, double si, int per_second = 0) {
  return fmt::format("{:.1f} {}{}", to_display(l.dimension, si) + 0.0, display_unit(l.dimension),
                     per_second ? "/s" : "");
}

// "-120.0..120.0 deg"
std::string shown_range(const PathLimits& l) {
  return fmt::format("{:.1f}..{:.1f} {}", to_display(l.dimension, l.lower) + 0.0, to_display(l.dimension, l.upper) + 0.0,
                     display_unit(l.dimension));
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
    return fmt::format("segment {} ({}): {}", k + 1, to_string(path_.segments()[std::size_t(k)].kind), where_on(s));
  }
  // "at 42 % (x 212.0 y -30.5 z 88.0 mm)"
  std::string where_on(double s) const {
    const Eigen::Vector3d p = path_.at(s).position * 1e3;
    return fmt::format("at {:.0f} % (x {:.1f} y {:.1f} z {:.1f} mm)", path_.segment_fraction(s) * 100, p.x() + 0.0,
                       p.y() + 0.0, p.z() + 0.0);
  }
  // The refusal at s ("segment 3 (LIN): at 42 % (...): " + why), naming chain joint `joint`
  // (-1: none).
  Error refuse_at(double s, const std::string& why, int joint = -1) const {
    PathRefusal r;
    r.segment = path_.segment_at(s);
    r.kind = path_.segments()[std::size_t(r.segment)].kind;
    r.fraction = path_.segment_fraction(s);
    r.point = path_.at(s).position;
    r.joint = joint;
    if (joint >= 0) r.joint_name = limits_[std::size_t(joint)].name;
    r.reason = fmt::format("{}: {}", where_on(s), why);
    return path_refusal(std::move(r));
  }

  Result<Solved> solve(double s, const JointVector& near) const {
    IkRequest request;
    request.target = compose(path_.at(s), tool_inverse_);
    if (nearest_) request.target = facing_the_position(request.target);
    request.nearest_orientation = nearest_;
    auto solutions = kin_.inverse(request, near);
    if (!solutions) return refuse_at(s, solutions.error().message);
    const IkSolution& best = solutions->front();
    return Solved{best.joints, best.configuration};
  }

  Status check_limits(double s, const JointVector& q) const {
    for (std::size_t j = 0; j < limits_.size(); ++j) {
      const PathLimits& l = limits_[j];
      const double v = q[Eigen::Index(j)];
      if (v < l.lower - 1e-9 || v > l.upper + 1e-9)
        return refuse_at(s, fmt::format("joint {} would be at {}, allowed {}", l.name, shown(l, v), shown_range(l)),
                         int(j));
    }
    return Ok{};
  }

  std::string singularity_note(const JointVector& q) const {
    const Singularity s = kin_.singularity(q, kNearSingularity);
    return s == Singularity::none ? "" : fmt::format(" near a singularity ({})", to_string(s));
  }

  Error too_fast(double s, const JointVector& q, int joint, double per_s) const {
    const PathLimits& l = limits_[std::size_t(joint)];
    return refuse_at(s,
                     fmt::format("joint {} would need {} at {:.0f} % of the programmed speed, allowed {}{}", l.name,
                                 shown(l, per_s * kMinPathRate, 1), kMinPathRate * 100, shown(l, l.velocity, 1),
                                 singularity_note(q)),
                     joint);
  }

  // The step a..b could not be made small in the joints by making it small in s: the
  // continuous solution ends there. Says whether at a joint limit (the kinematics keeps
  // its solutions inside the limits) or at a change of configuration.
  Error refuse_jump(double a, const Solved& qa, const Solved& qb) const {
    for (std::size_t j = 0; j < limits_.size(); ++j) {
      const PathLimits& lj = limits_[j];
      const double v = qa.joints[Eigen::Index(j)];
      if (std::min(std::abs(v - lj.lower), std::abs(v - lj.upper)) < 1e-3)
        return refuse_at(a, fmt::format("joint {} would leave its limits at {}, allowed {}", lj.name, shown(lj, v),
                                        shown_range(lj)),
                         int(j));
    }
    const std::string change = same(qa.configuration, qb.configuration)
                                   ? ""
                                   : fmt::format(" ({} -> {})", describe(qa.configuration), describe(qb.configuration));
    const int joint = jumping_joint(qa, qb);
    return refuse_at(a,
                     fmt::format("{}, a change of configuration{}{}; the arm cannot follow the path through there "
                                 "(move around it, or split the path with a PTP)",
                                 jump_words(qa, qb, joint), change, singularity_note(qa.joints)),
                     joint);
  }

  // "the joints would jump: joint servo6 from 0.0 deg to 6.3 deg": the joint whose step is
  // the largest for its step limit.
  int jumping_joint(const Solved& qa, const Solved& qb) const {
    int joint = 0;
    double worst = 0;
    for (std::size_t j = 0; j < limits_.size(); ++j) {
      const double d = std::abs(qb.joints[Eigen::Index(j)] - qa.joints[Eigen::Index(j)]) / step_limit(j);
      if (d > worst) {
        worst = d;
        joint = int(j);
      }
    }
    return joint;
  }
  std::string jump_words(const Solved& qa, const Solved& qb, int joint) const {
    const PathLimits& l = limits_[std::size_t(joint)];
    return fmt::format("the joints would jump: joint {} from {} to {}", l.name, shown(l, qa.joints[joint]),
                       shown(l, qb.joints[joint]));
  }

  // The path starts at a singularity (kSingularStart) and cannot leave it along the path
  // (`why`): leaving along the lost direction needs the joints to jump (the xArm's base to
  // the line's heading) or to move infinitely fast at first (the elbow bends as the square
  // root of the distance from a stretched arm). Refused with what to do, instead of a jump
  // at 0 % or a path slowed to a crawl over its whole length.
  Error refuse_singular_start(const std::string& why, int joint) const {
    return refuse_at(0, fmt::format("the path starts at a singularity ({}), where {}: a straight line cannot start "
                                    "there; move the arm away from it first with a joint move (PTP: a move to a "
                                    "tool point without a straight line, or a ptp line before the path), then start "
                                    "the path",
                                    to_string(start_singularity_), why),
                     joint);
  }

  // The pose at b cannot be reached, the one at a (solved as qa) can: narrows it down by
  // halves to where the path leaves what the arm reaches, and refuses with the kinematics'
  // reason there.
  Error refuse_unreachable(double a, Solved qa, double b, Error at_b) const {
    for (int i = 0; i < 40; ++i) {
      const double m = (a + b) / 2;
      if (m <= a || m >= b) break;
      auto qm = solve(m, qa.joints);
      if (qm) {
        a = m;
        qa = *qm;
      } else {
        b = m;
        at_b = qm.error();
      }
    }
    return at_b;
  }

  // The largest step of joint j between two samples: 1 deg, or 1 mm for a prismatic joint.
  double step_limit(std::size_t j) const {
    return limits_[j].dimension == Dimension::angle ? kPathSampleJointAngle : kPathSampleJointLength;
  }
  bool joints_far(const JointVector& a, const JointVector& b) const {
    for (std::size_t j = 0; j < limits_.size(); ++j)
      if (std::abs(b[Eigen::Index(j)] - a[Eigen::Index(j)]) > step_limit(j)) return true;
    return false;
  }

  // Samples of the stretch [from, to] (between two rests): each segment's own step (1 mm
  // and 1 deg at its programmed rates), then halved wherever two neighbours are further apart.
  Result<std::vector<double>> grid(double from, double to) const {
    std::vector<double> s{from};
    for (const BuiltSegment& g : path_.segments()) {
      if (g.end_s <= from || g.start_s >= to) continue;
      const double t = g.end_s - g.start_s;
      if (!(t > 0)) continue;  // no nominal time: nothing between its ends to sample
      double step = t;
      if (g.length > 0) step = std::min(step, kPathSampleLength * t / g.length);
      if (g.angle > 0) step = std::min(step, kPathSampleAngle * t / g.angle);
      const double n = std::ceil(t / step);
      // Written so that a NaN (an infinite length over an infinite time) is refused too:
      // int(NaN) would leave the stretch without samples.
      if (!(n >= 1 && n <= double(kMaxSamples)))
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

  // Derivatives by finite differences over one stretch [first, last] of the samples. A
  // stretch of one sample (a rest with no motion after it) has none: zero, and nothing past
  // `last` is read.
  static void differentiate(CheckedPath& c, std::size_t first, std::size_t last) {
    const std::vector<double>& s = c.s;
    const Eigen::Index n = c.joints[first].size();
    for (std::size_t i = first; i <= last; ++i) {
      c.dq_ds[i] = JointVector::Zero(n);
      c.d2q_ds2[i] = JointVector::Zero(n);
    }
    if (last <= first) return;
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
    start_singularity_ = kin_.singularity(first->joints, kSingularStart);
    Solved previous = *first;
    double previous_s = 0;
    double from = 0;
    const double narrowest = kJumpWidth * std::max(1.0, path_.duration());
    for (double rest : path_.rests()) {
      auto s = grid(from, rest);
      if (!s) return s.error();
      const std::size_t stretch_first = out.s.size();
      auto accept = [&](double si, const Solved& here) -> Status {
        if (auto ok = check_limits(si, here.joints); !ok) return ok;
        if (out.s.size() >= kMaxSamples)
          return refuse(fmt::format("the path needs more than {} samples to check; split it", kMaxSamples));
        out.s.push_back(si);
        out.joints.push_back(here.joints);
        previous = here;
        previous_s = si;
        return Ok{};
      };
      // The stretch's first sample: the path's start, or the rest again (starting the next stretch).
      if (auto ok = accept(from, previous); !ok) return ok.error();
      for (std::size_t i = 1; i < s->size(); ++i) {
        // Halve the step until no joint moves more than its step limit; a step that stays
        // large as it shrinks to nothing is a jump.
        std::vector<double> pending{(*s)[i]};
        while (!pending.empty()) {
          const double b = pending.back();
          auto q = solve(b, previous.joints);
          if (!q) return refuse_unreachable(previous_s, previous, b, q.error());
          if (joints_far(previous.joints, q->joints)) {
            const double m = (previous_s + b) / 2;
            if (b - previous_s > narrowest && m > previous_s && m < b) {
              pending.push_back(m);
              continue;
            }
            // Still at the singular start (the first steps may stay on the base axis).
            if (start_singularity_ != Singularity::none && !joints_far(first->joints, previous.joints)) {
              const int joint = jumping_joint(previous, *q);
              return refuse_singular_start(jump_words(previous, *q, joint), joint);
            }
            return refuse_jump(previous_s, previous, *q);
          }
          if (auto ok = accept(b, *q); !ok) return ok.error();
          pending.pop_back();
        }
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
    }
    // From a singular start, a joint's speed at the first sample is only the finite
    // difference's guess at an unbounded one (the elbow bends as the square root of the
    // distance from a stretched arm): slowed there, the path cannot start there.
    if (start_singularity_ != Singularity::none && !out.rate_limit.empty() && out.rate_limit[0] < 1) {
      const PathLimits& l = limits_[std::size_t(limiting[0])];
      return refuse_singular_start(fmt::format("joint {} would have to move faster the closer the tool is to it ({} "
                                               "at full speed over the first step, allowed {})",
                                               l.name, shown(l, std::abs(out.dq_ds[0][limiting[0]]), 1),
                                               shown(l, l.velocity, 1)),
                                   limiting[0]);
    }
    if (out.max_rate < kMinPathRate) {  // refused where it is slowest
      const std::size_t i = std::size_t(std::min_element(out.rate_limit.begin(), out.rate_limit.end()) - out.rate_limit.begin());
      const int j = limiting[i];
      return too_fast(out.s[i], out.joints[i], j, std::abs(out.dq_ds[i][j]));
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
  Singularity start_singularity_ = Singularity::none;  // of the path's first sample (kSingularStart)
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
  if (!std::isfinite(path.duration()) || !(path.duration() > 0))
    return refuse(fmt::format("the path's nominal duration is {} s; it must be finite and above 0", path.duration()));
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

namespace {

// The step [a, a + 1] of the samples that holds `at` (clamped to the path), with t in [0, 1].
struct Step {
  std::size_t a = 0;
  double t = 0;
};
Step step_at(const std::vector<double>& s, double at) {
  if (s.size() < 2 || at <= s.front()) return {0, 0};
  if (at >= s.back()) return {s.size() - 2, 1};
  // The first sample after `at`: its predecessor starts a step of positive length (a rest's
  // two samples share one s).
  const std::size_t b = std::size_t(std::upper_bound(s.begin(), s.end(), at) - s.begin());
  return {b - 1, (at - s[b - 1]) / (s[b] - s[b - 1])};
}

}  // namespace

CheckedPath::Joints CheckedPath::joints_with_rates(double at) const {
  if (s.empty()) return {};
  if (s.size() == 1) return {joints[0], dq_ds[0], d2q_ds2[0]};
  const auto [a, t] = step_at(s, at);
  const std::size_t b = a + 1;
  const double h = s[b] - s[a];
  const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
  const double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
  const double d00 = 6 * t * t - 6 * t, d10 = 3 * t * t - 4 * t + 1, d01 = -d00, d11 = 3 * t * t - 2 * t;
  Joints out;
  out.position = h00 * joints[a] + h10 * h * dq_ds[a] + h01 * joints[b] + h11 * h * dq_ds[b];
  out.dq_ds = (d00 * joints[a] + d01 * joints[b]) / h + d10 * dq_ds[a] + d11 * dq_ds[b];
  out.d2q_ds2 = (1 - t) * d2q_ds2[a] + t * d2q_ds2[b];
  return out;
}

JointVector CheckedPath::joints_at(double at) const { return joints_with_rates(at).position; }

double CheckedPath::rate_limit_at(double at) const {
  if (rate_limit.empty()) return 0;
  if (rate_limit.size() == 1) return rate_limit[0];
  const Step step = step_at(s, at);
  return std::min(rate_limit[step.a], rate_limit[step.a + 1]);
}

JointVector CheckedPath::joints_at(double at, const JointVector& near) const {
  const JointVector interpolated = joints_at(at);
  if (!solver || solver->kinematics == nullptr) return interpolated;
  IkRequest request;
  request.target = compose(solver->path.at(at), solver->tool_inverse);
  if (solver->nearest) request.target = facing_the_position(request.target);
  request.nearest_orientation = solver->nearest;
  auto solutions = solver->kinematics->inverse(request, near.size() == interpolated.size() ? near : interpolated);
  if (!solutions) return interpolated;
  return solutions->front().joints;
}

}  // namespace armctl::motion

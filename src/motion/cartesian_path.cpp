#include "motion/cartesian_path.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <fmt/core.h>

namespace armctl::motion {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kQuaternionSlack = 1e-6;  // as the kinematics accept a unit quaternion
constexpr double kNoMotion = 1e-9;         // m and rad: a segment below both does not move
constexpr double kCircPointGap = 1e-6;     // m: CIRC points closer than this coincide

Error refuse(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

// An error of segment `index` (its message the reason) as that segment's refusal.
Error at_segment(std::size_t index, SegmentKind kind, const Error& e) {
  PathRefusal r;
  r.segment = int(index);
  r.kind = kind;
  r.reason = e.message;
  return path_refusal(std::move(r));
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// Rotation from a to b in the base frame as a rotation vector (shortest way).
Eigen::Vector3d rotation_between(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  Eigen::Quaterniond delta = b * a.conjugate();
  if (delta.w() < 0) delta.coeffs() = -delta.coeffs();
  const double sine = delta.vec().norm();
  if (sine < 1e-300) return Eigen::Vector3d::Zero();
  return delta.vec() / sine * (2 * std::atan2(sine, delta.w()));
}

Eigen::Quaterniond exp_rotation(const Eigen::Vector3d& rotation) {
  const double angle = rotation.norm();
  if (angle < 1e-300) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation / angle));
}

// Blend weights: position uses the cubic smoothstep (velocity superposition, so the
// acceleration stays continuous); orientation slerps between the two segments' extended
// orientations with the quintic one, whose first two derivatives vanish at both ends.
double cubic(double x) { return x * x * (3 - 2 * x); }
double cubic_rate(double x) { return 6 * x * (1 - x); }
double cubic_integral(double x) { return x * x * x - x * x * x * x / 2; }  // of cubic, from 0
double quintic(double x) { return x * x * x * (10 + x * (-15 + 6 * x)); }

// 10-point Gauss-Legendre nodes and weights on [-1, 1] (Newton on P10 from the Chebyshev
// guesses): exact for polynomials up to degree 19, so for the cubic weight times a CIRC's
// velocity (one trigonometric term over at most half a turn) the error is below 1e-15.
struct GaussLegendre {
  std::array<double, 10> x{}, w{};
  GaussLegendre() {
    constexpr int n = 10;
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (n + 0.5));
      double dp = 1;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-16) break;
      }
      x[std::size_t(i)] = z;
      w[std::size_t(i)] = 2 / ((1 - z * z) * dp * dp);
    }
  }
};
const GaussLegendre& gauss_legendre() {
  static const GaussLegendre g;
  return g;
}

// One segment on its own, extended past both ends (a LIN along its line, a CIRC around its
// circle, the orientation at its constant rate), at global nominal time s.
struct Sample {
  Eigen::Vector3d position, velocity, acceleration;
};

double nominal_time(const BuiltSegment& g) { return g.end_s - g.start_s; }

Sample segment_point(const BuiltSegment& g, double s) {
  const double t = nominal_time(g);
  const double u = s - g.start_s;
  if (g.kind == SegmentKind::lin) {
    const Eigen::Vector3d v = (g.target.position - g.start.position) / t;
    return {g.start.position + v * u, v, Eigen::Vector3d::Zero()};
  }
  const double rate = g.arc / t;
  const double theta = rate * u;
  const double c = std::cos(theta), sn = std::sin(theta);
  return {g.centre + g.radius * (c * g.e1 + sn * g.e2), g.radius * rate * (-sn * g.e1 + c * g.e2),
          -g.radius * rate * rate * (c * g.e1 + sn * g.e2)};
}

Eigen::Vector3d segment_angular_velocity(const BuiltSegment& g) {
  return rotation_between(g.start.orientation, g.target.orientation) / nominal_time(g);
}

Eigen::Quaterniond segment_orientation(const BuiltSegment& g, double s) {
  return (exp_rotation(segment_angular_velocity(g) * (s - g.start_s)) * g.start.orientation).normalized();
}

Result<Pose> checked_pose(const Pose& pose, const std::string& what) {
  if (!finite(pose.position)) return refuse(fmt::format("{}: the position is not a finite number", what));
  if (!pose.orientation.coeffs().allFinite())
    return refuse(fmt::format("{}: the orientation is not a finite number", what));
  const double norm = pose.orientation.norm();
  if (std::abs(norm - 1) > kQuaternionSlack)
    return refuse(fmt::format("{}: the orientation is not a unit quaternion (norm {:.9g}); allowed: norm 1 within {}",
                              what, norm, kQuaternionSlack));
  Pose out = pose;
  out.orientation.normalize();
  return out;
}

Status check_rate(double value, const char* name, const char* unit) {
  if (!std::isfinite(value) || value <= 0)
    return refuse(fmt::format("{} {} is not allowed; it must be a finite number > 0 ({})", name, value, unit));
  return Ok{};
}

// Circle through a, b (via) and c: fills centre, radius, e1, e2 and arc of `g`.
Status build_circle(BuiltSegment& g, const Eigen::Vector3d& via) {
  const Eigen::Vector3d a = g.start.position, c = g.target.position;
  if ((via - a).norm() < kCircPointGap)
    return refuse("the via point is at the segment's start; it must lie on the arc between start and target");
  if ((c - via).norm() < kCircPointGap)
    return refuse("the via point is at the target; it must lie on the arc between start and target");
  if ((c - a).norm() < kCircPointGap)
    return refuse("the target is at the segment's start; a full circle needs two CIRC segments");
  const Eigen::Vector3d chord = (c - a).normalized();
  const Eigen::Vector3d off = (via - a) - (via - a).dot(chord) * chord;
  if (off.norm() < kCircPointGap)
    return refuse(fmt::format("start, via and target lie on one line (the via point is {:.6f} mm from the line "
                              "through start and target); a circle needs it at least {} mm off it",
                              off.norm() * 1e3, kCircPointGap * 1e3));
  const Eigen::Vector3d u = via - a, w = c - a, n = u.cross(w);
  g.centre = a + (u.squaredNorm() * w - w.squaredNorm() * u).cross(n) / (2 * n.squaredNorm());
  g.radius = (a - g.centre).norm();
  g.e1 = (a - g.centre) / g.radius;
  g.e2 = n.normalized().cross(g.e1);
  auto angle_of = [&](const Eigen::Vector3d& p) {
    const double t = std::atan2((p - g.centre).dot(g.e2), (p - g.centre).dot(g.e1));
    return t < 0 ? t + 2 * kPi : t;
  };
  g.arc = angle_of(c);
  // With the plane's normal taken from start -> via -> target, the via always comes first:
  // this holds by construction, checked so that a numeric corner case cannot pass unseen.
  if (!(angle_of(via) < g.arc))
    return refuse("the via point is not between start and target along the arc");
  g.length = g.radius * g.arc;
  return Ok{};
}

// The blend half-width at the corner between segments a and b (docs/paths.md): two LINs
// leave and join within `zone` with |v| tau <= zone, which keeps the whole blend within
// zone of the corner; with a CIRC the velocity turns inside the window as well, and
// 11/8 vmax tau <= zone is what bounds the blend within zone of the corner there.
double blend_half_width(const BuiltSegment& a, const BuiltSegment& b, double zone) {
  const double ta = nominal_time(a), tb = nominal_time(b);
  double tau = std::min(ta, tb) / 2;
  const double va = a.length / ta, vb = b.length / tb;
  if (a.kind == SegmentKind::lin && b.kind == SegmentKind::lin) {
    if (va > 0) tau = std::min(tau, zone / va);
    if (vb > 0) tau = std::min(tau, zone / vb);
  } else {
    const double vmax = std::max(va, vb);
    if (vmax > 0) tau = std::min(tau, zone * 8 / (11 * vmax));
  }
  return tau;
}

}  // namespace

const char* to_string(SegmentKind kind) { return kind == SegmentKind::lin ? "LIN" : "CIRC"; }

Result<CartesianPath> build_cartesian_path(const Pose& start, std::span<const PathSegment> segments) {
  if (segments.empty()) return refuse("a path needs at least one segment");
  auto from = checked_pose(start, "the path's start pose");
  if (!from) return from.error();
  CartesianPath path;
  Pose here = *from;
  double s = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const PathSegment& in = segments[i];
    auto fail = [&](const Error& e) { return at_segment(i, in.kind, e); };
    if (in.kind != SegmentKind::lin && in.kind != SegmentKind::circ)
      return refuse(fmt::format("segment {}: unknown kind; allowed: LIN, CIRC", i + 1));
    auto target = checked_pose(in.target, "target");
    if (!target) return fail(target.error());
    if (auto ok = check_rate(in.speed, "speed", "m/s of the tool point"); !ok) return fail(ok.error());
    if (auto ok = check_rate(in.angular_speed, "angular speed", "rad/s of the tool"); !ok) return fail(ok.error());
    if (!std::isfinite(in.zone) || in.zone < 0)
      return fail(refuse(fmt::format("zone {} is not allowed; it must be a finite number >= 0 (m; 0 = stop exactly "
                                     "at the segment's end)",
                                     in.zone)));
    BuiltSegment g;
    g.kind = in.kind;
    g.start = here;
    g.target = *target;
    g.speed = in.speed;
    g.angular_speed = in.angular_speed;
    g.angle = rotation_between(g.start.orientation, g.target.orientation).norm();
    if (in.kind == SegmentKind::lin) {
      g.length = (g.target.position - g.start.position).norm();
      if (g.length < kNoMotion && g.angle < kNoMotion)
        return fail(refuse("the target is where the segment starts (it neither moves nor turns the tool); "
                           "remove it or change its target"));
      if (g.length < kNoMotion) g.target.position = g.start.position;  // a pure turn
    } else {
      if (!finite(in.via)) return fail(refuse("the via point is not a finite number"));
      if (auto ok = build_circle(g, in.via); !ok) return fail(ok.error());
    }
    // Coordinates of 1e200 m are finite, their distance is not; and a speed of 1e300 m/s
    // makes a segment take no time at all: either would leave nothing to sample.
    const double nominal = std::max(g.length / g.speed, g.angle / g.angular_speed);
    if (!std::isfinite(g.length) || !std::isfinite(nominal))
      return fail(refuse(fmt::format("the target is {:.6g} m from the segment's start, taking {:.6g} s at {:.6g} m/s; "
                                "a segment's length and time must be finite numbers",
                                g.length, nominal, g.speed)));
    if (!(s + nominal > s))
      return fail(refuse(fmt::format("at {:.6g} m/s and {:.6g} rad/s its {:.6g} m and {:.6g} rad take no time after the "
                                "{:.6g} s of path before it; lower its speed",
                                g.speed, g.angular_speed, g.length, g.angle, s)));
    g.start_s = s;
    g.end_s = s + nominal;
    s = g.end_s;
    here = g.target;
    path.segments_.push_back(g);
  }
  for (std::size_t i = 0; i + 1 < path.segments_.size(); ++i) {
    const double zone = segments[i].zone;
    if (zone > 0) path.segments_[i].blend = blend_half_width(path.segments_[i], path.segments_[i + 1], zone);
  }
  return path;
}

Error path_refusal(PathRefusal r) {
  std::string message = fmt::format("segment {} ({}): {}", r.segment + 1, to_string(r.kind), r.reason);
  return Error{ErrorKind::invalid_argument, std::move(message), std::move(r)};
}

double CartesianPath::duration() const { return segments_.empty() ? 0 : segments_.back().end_s; }

int CartesianPath::segment_at(double s) const {
  // The first segment ending at or after s (segments are in order of s).
  const auto it = std::lower_bound(segments_.begin(), segments_.end(), s,
                                   [](const BuiltSegment& g, double value) { return g.end_s < value; });
  if (it == segments_.end()) return static_cast<int>(segments_.size()) - 1;
  return static_cast<int>(it - segments_.begin());
}

double CartesianPath::segment_fraction(double s) const {
  const BuiltSegment& g = segments_[std::size_t(segment_at(s))];
  return std::clamp((s - g.start_s) / nominal_time(g), 0.0, 1.0);
}

std::vector<double> CartesianPath::rests() const {
  std::vector<double> out;
  for (const BuiltSegment& g : segments_)
    if (g.blend == 0 || &g == &segments_.back()) out.push_back(g.end_s);
  return out;
}

namespace {

// The corner whose blend window holds s: the index of the segment it ends, or -1.
int blend_corner(const std::vector<BuiltSegment>& segments, int k, double s) {
  const BuiltSegment& g = segments[std::size_t(k)];
  if (k > 0 && segments[std::size_t(k - 1)].blend > 0 && s < g.start_s + segments[std::size_t(k - 1)].blend)
    return k - 1;
  if (k + 1 < int(segments.size()) && g.blend > 0 && s > g.end_s - g.blend) return k;
  return -1;
}

struct Blended {
  Sample point;
  Eigen::Vector3d angular_velocity;
};

// Velocity superposition over the window [sc - tau, sc + tau] of the corner between a and b:
// v = va + (vb - va) w(sigma), so p = pa(s) + integral of w (vb - va) from the window's start.
Sample blend_point(const BuiltSegment& a, const BuiltSegment& b, double s) {
  const double tau = a.blend, sc = a.end_s, t0 = sc - tau;
  const double sigma = (s - t0) / (2 * tau);
  const Sample pa = segment_point(a, s), pb = segment_point(b, s);
  Sample out;
  out.velocity = pa.velocity + cubic(sigma) * (pb.velocity - pa.velocity);
  out.acceleration = pa.acceleration + cubic(sigma) * (pb.acceleration - pa.acceleration) +
                     cubic_rate(sigma) / (2 * tau) * (pb.velocity - pa.velocity);
  Eigen::Vector3d offset;
  if (a.kind == SegmentKind::lin && b.kind == SegmentKind::lin) {
    offset = 2 * tau * cubic_integral(sigma) * (pb.velocity - pa.velocity);
  } else {
    offset.setZero();
    const GaussLegendre& gl = gauss_legendre();
    const double half = (s - t0) / 2, mid = (s + t0) / 2;
    for (std::size_t k = 0; k < gl.x.size(); ++k) {
      const double t = mid + half * gl.x[k];
      offset += gl.w[k] * half * cubic((t - t0) / (2 * tau)) * (segment_point(b, t).velocity - segment_point(a, t).velocity);
    }
  }
  out.position = pa.position + offset;
  return out;
}

Eigen::Quaterniond blend_orientation(const BuiltSegment& a, const BuiltSegment& b, double s) {
  const double sigma = std::clamp((s - (a.end_s - a.blend)) / (2 * a.blend), 0.0, 1.0);
  Eigen::Quaterniond qa = segment_orientation(a, s), qb = segment_orientation(b, s);
  return qa.slerp(quintic(sigma), qb).normalized();
}

}  // namespace

Pose CartesianPath::at(double s) const {
  s = std::clamp(s, 0.0, duration());
  const int k = segment_at(s);
  const int corner = blend_corner(segments_, k, s);
  Pose out;
  if (corner < 0) {
    const BuiltSegment& g = segments_[std::size_t(k)];
    if (s >= g.end_s) return g.target;  // exactly, not up to rounding
    out.position = segment_point(g, s).position;
    out.orientation = segment_orientation(g, s);
    return out;
  }
  const BuiltSegment &a = segments_[std::size_t(corner)], &b = segments_[std::size_t(corner + 1)];
  out.position = blend_point(a, b, s).position;
  out.orientation = blend_orientation(a, b, s);
  return out;
}

PathRates CartesianPath::rates(double s) const {
  s = std::clamp(s, 0.0, duration());
  int k = segment_at(s);
  // At a rest the segment after it: the direction the path leaves in.
  if (k + 1 < int(segments_.size()) && s >= segments_[std::size_t(k)].end_s && segments_[std::size_t(k)].blend == 0)
    ++k;
  const int corner = blend_corner(segments_, k, s);
  PathRates out;
  if (corner < 0) {
    const BuiltSegment& g = segments_[std::size_t(k)];
    const Sample p = segment_point(g, s);
    out.velocity = p.velocity;
    out.acceleration = p.acceleration;
    out.angular_velocity = segment_angular_velocity(g);
    return out;
  }
  const BuiltSegment &a = segments_[std::size_t(corner)], &b = segments_[std::size_t(corner + 1)];
  const Sample p = blend_point(a, b, s);
  out.velocity = p.velocity;
  out.acceleration = p.acceleration;
  // The slerp blend has no short closed form for its rates: central differences, with
  // steps of 1e-5 of the window for the angular velocity and 1e-3 for its derivative
  // (truncation and rounding both below 1e-7 of the rates; the weight is C2, so the
  // window's edges need no care).
  const double hv = 1e-5 * a.blend, ha = 1e-3 * a.blend;
  out.angular_velocity =
      rotation_between(blend_orientation(a, b, s - hv), blend_orientation(a, b, s + hv)) / (2 * hv);
  const Eigen::Quaterniond q0 = blend_orientation(a, b, s - ha), q1 = blend_orientation(a, b, s),
                           q2 = blend_orientation(a, b, s + ha);
  out.angular_acceleration = (rotation_between(q1, q2) - rotation_between(q0, q1)) / (ha * ha);
  return out;
}

double CartesianPath::corner_deviation(int index) const {
  if (index < 0 || index + 1 >= int(segments_.size())) return 0;
  const BuiltSegment& a = segments_[std::size_t(index)];
  if (a.blend == 0) return 0;
  return (blend_point(a, segments_[std::size_t(index + 1)], a.end_s).position - a.target.position).norm();
}

}  // namespace armctl::motion

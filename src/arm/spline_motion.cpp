#include "arm/spline_motion.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "core/quantity.hpp"

namespace armctl::arm {

namespace {

Error refused(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

// One joint between two knots: a quintic (or cubic, a = 0 and no acceleration given)
// Hermite polynomial in the time since the segment's start.
struct Segment {
  double t0 = 0, length = 1;
  double c[6] = {0, 0, 0, 0, 0, 0};  // position = sum c[k] s^k, s in seconds

  static Segment hermite(double t0, double length, double p0, double v0, double a0, double p1, double v1, double a1,
                         bool quintic) {
    Segment s;
    s.t0 = t0;
    s.length = length;
    const double T = length, T2 = T * T, T3 = T2 * T;
    const double d = p1 - p0;
    s.c[0] = p0;
    s.c[1] = v0;
    if (quintic) {
      const double T4 = T3 * T, T5 = T4 * T;
      s.c[2] = a0 / 2;
      s.c[3] = (20 * d - (8 * v1 + 12 * v0) * T - (3 * a0 - a1) * T2) / (2 * T3);
      s.c[4] = (-30 * d + (14 * v1 + 16 * v0) * T + (3 * a0 - 2 * a1) * T2) / (2 * T4);
      s.c[5] = (12 * d - 6 * (v1 + v0) * T - (a0 - a1) * T2) / (2 * T5);
    } else {
      s.c[2] = (3 * d - (2 * v0 + v1) * T) / T2;
      s.c[3] = (-2 * d + (v0 + v1) * T) / T3;
    }
    return s;
  }

  void sample(double t, double& p, double& v, double& a) const {
    const double s = std::clamp(t - t0, 0.0, length);
    p = c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * (c[4] + s * c[5]))));
    v = c[1] + s * (2 * c[2] + s * (3 * c[3] + s * (4 * c[4] + s * 5 * c[5])));
    a = 2 * c[2] + s * (6 * c[3] + s * (12 * c[4] + s * 20 * c[5]));
  }
};

// Every joint's segments (the model's order) and the knot times.
struct Spline {
  std::vector<double> knots;                 // 0, then each point's time
  std::vector<std::vector<Segment>> joints;  // [joint][segment]

  void sample(double t, std::vector<double>& p, std::vector<double>& v, std::vector<double>& a) const {
    p.resize(joints.size());
    v.resize(joints.size());
    a.resize(joints.size());
    t = std::clamp(t, 0.0, knots.back());
    const auto it = std::upper_bound(knots.begin(), knots.end(), t);
    std::size_t k = it == knots.begin() ? 0 : std::size_t(it - knots.begin()) - 1;
    k = std::min(k, knots.size() - 2);
    for (std::size_t j = 0; j < joints.size(); ++j) joints[j][k].sample(t, p[j], v[j], a[j]);
  }
};

std::string value(const ArmModel& model, std::size_t joint, double si) {
  return format_quantity(model.joints[joint].dimension, si);
}

// A joint rate as the Arm API writes it ("180 deg/s", "0.5 m/s^2"): per s (power 1) or per s^2 (2).
std::string rate(const ArmModel& model, std::size_t joint, double si, int power) {
  return format_quantity(model.joints[joint].dimension, si, power);
}

// Velocities at the knots where the request gives none: 0 at both ends, at an inner knot
// the mean of the two neighbouring slopes, 0 where they differ in sign (the joint turns
// back there: no overshoot past the point).
double estimated_velocity(double p_prev, double t_prev, double p, double t, double p_next, double t_next) {
  const double s0 = (p - p_prev) / (t - t_prev), s1 = (p_next - p) / (t_next - t);
  if (s0 * s1 <= 0) return 0;
  return 0.5 * (s0 + s1);
}

}  // namespace

Result<SplinePlan> plan_spline(const ArmModel& model, const std::vector<double>& from, const SplineRequest& request) {
  const std::size_t all = std::size_t(model.joint_count());
  if (from.size() != all) return refused(fmt::format("the arm's positions are not known ({} values)", from.size()));
  if (request.points.empty()) return refused("the trajectory has no points");

  // Sizes, finite values, times, position limits: each point as given.
  double previous_time = 0;
  bool velocities = true, accelerations = true;
  for (std::size_t k = 0; k < request.points.size(); ++k) {
    const auto& p = request.points[k];
    const std::string where = fmt::format("point {} (at {:.3f} s)", k, p.time);
    if (p.positions.size() != all || (!p.velocities.empty() && p.velocities.size() != all) ||
        (!p.accelerations.empty() && p.accelerations.size() != all))
      return refused(fmt::format("point {} has not one value per joint of arm {} ({})", k, model.name, all));
    if (!std::isfinite(p.time)) return refused(fmt::format("point {}: time_from_start is not finite", k));
    if (p.time > request.longest)
      return refused(fmt::format("point {}: time_from_start {:.3f} s is beyond the longest trajectory, {:.0f} s", k,
                                 p.time, request.longest));
    if (p.time < 0)
      return refused(fmt::format("{}: time_from_start is negative; times must be 0 or more and rising", where));
    if (k > 0 && p.time <= previous_time)
      return refused(fmt::format("{}: times must rise from point to point, but point {} is at {:.3f} s", where, k - 1,
                                 previous_time));
    previous_time = p.time;
    velocities = velocities && !p.velocities.empty();
    accelerations = accelerations && !p.accelerations.empty();
    for (std::size_t j = 0; j < all; ++j) {
      if (!p.positions[j]) continue;
      const auto& jm = model.joints[j];
      const bool finite = std::isfinite(*p.positions[j]) && (p.velocities.empty() || std::isfinite(p.velocities[j])) &&
                          (p.accelerations.empty() || std::isfinite(p.accelerations[j]));
      if (!finite) return refused(fmt::format("{}: joint {} has a value that is not finite", where, jm.name));
      if (!jm.limits.contains(*p.positions[j]))
        return refused(fmt::format("{}: joint {} at {} is beyond its limits {}..{}", where, jm.name,
                                   value(model, j, *p.positions[j]), value(model, j, jm.limits.lower),
                                   value(model, j, jm.limits.upper)));
    }
  }
  const auto& last = request.points.back();
  if (!last.velocities.empty())
    for (std::size_t j = 0; j < all; ++j)
      if (last.positions[j] && last.velocities[j] != 0)
        return refused(fmt::format("the last point gives joint {} a velocity of {}: the arm ends a trajectory at "
                                   "rest, so the last velocities must be 0",
                                   model.joints[j].name, rate(model, j, last.velocities[j], 1)));

  // The knots: where the arm stands at 0 (a first point at 0 must be there), then the points.
  std::vector<double> times{0};
  std::vector<std::vector<double>> pos{from}, vel{std::vector<double>(all, 0.0)}, acc{std::vector<double>(all, 0.0)};
  std::size_t first = 0;
  if (request.points.front().time == 0) {
    const auto& p = request.points.front();
    for (std::size_t j = 0; j < all; ++j) {
      if (!p.positions[j]) continue;
      const bool angle = model.joints[j].dimension == Dimension::angle;
      if (std::abs(*p.positions[j] - from[j]) > (angle ? request.start_angle_tolerance : request.start_length_tolerance))
        return refused(fmt::format("point 0 is at 0 s, so it must be where the arm stands, but joint {} is at {} "
                                   "and point 0 puts it at {} (give the first point a time after 0 to move there)",
                                   model.joints[j].name, value(model, j, from[j]), value(model, j, *p.positions[j])));
      if (!p.velocities.empty() && p.velocities[j] != 0)
        return refused("point 0 is at 0 s, so its velocities must be 0 (the arm starts at rest)");
    }
    first = 1;
  }
  for (std::size_t k = first; k < request.points.size(); ++k) {
    const auto& p = request.points[k];
    std::vector<double> q = from, v(all, 0.0), a(all, 0.0);
    for (std::size_t j = 0; j < all; ++j) {
      if (!p.positions[j]) continue;
      q[j] = *p.positions[j];
      if (velocities) v[j] = p.velocities[j];
      if (accelerations) a[j] = p.accelerations[j];
    }
    times.push_back(p.time);
    pos.push_back(q);
    vel.push_back(v);
    acc.push_back(a);
  }
  if (times.size() < 2)
    return refused("the trajectory's only point is at 0 s, where the arm stands: nothing to do (give it a time after 0)");
  if (!velocities)
    for (std::size_t k = 1; k + 1 < times.size(); ++k)
      for (std::size_t j = 0; j < all; ++j)
        vel[k][j] = estimated_velocity(pos[k - 1][j], times[k - 1], pos[k][j], times[k], pos[k + 1][j], times[k + 1]);
  // The start and the end are at rest whatever was given.
  std::fill(vel.front().begin(), vel.front().end(), 0.0);
  std::fill(vel.back().begin(), vel.back().end(), 0.0);
  std::fill(acc.front().begin(), acc.front().end(), 0.0);
  std::fill(acc.back().begin(), acc.back().end(), 0.0);

  auto spline = std::make_shared<Spline>();
  spline->knots = times;
  spline->joints.resize(all);
  for (std::size_t j = 0; j < all; ++j)
    for (std::size_t k = 0; k + 1 < times.size(); ++k)
      spline->joints[j].push_back(Segment::hermite(times[k], times[k + 1] - times[k], pos[k][j], vel[k][j], acc[k][j],
                                                   pos[k + 1][j], vel[k + 1][j], acc[k + 1][j], accelerations));

  // The whole motion within the limits: sampled at 200 Hz and at least 50 times a segment.
  std::vector<double> p, v, a;
  for (std::size_t k = 0; k + 1 < times.size(); ++k) {
    const double length = times[k + 1] - times[k];
    const int steps = std::max(50, int(std::ceil(length * 200)));
    for (int s = 0; s <= steps; ++s) {
      const double t = times[k] + length * s / steps;
      spline->sample(t, p, v, a);
      for (std::size_t j = 0; j < all; ++j) {
        const auto& jm = model.joints[j];
        if (!jm.limits.contains(p[j], 1e-9))
          return refused(fmt::format("at {:.3f} s (on the way to point {}) joint {} would pass {}, beyond its limits "
                                     "{}..{}: add points or move them inside",
                                     t, k + first, jm.name, value(model, j, p[j]), value(model, j, jm.limits.lower),
                                     value(model, j, jm.limits.upper)));
        if (std::abs(v[j]) > jm.limits.velocity * (1 + 1e-6))
          return refused(fmt::format("at {:.3f} s joint {} would move at {}, beyond its velocity limit {}: give the "
                                     "points more time",
                                     t, jm.name, rate(model, j, std::abs(v[j]), 1), rate(model, j, jm.limits.velocity, 1)));
        if (std::abs(a[j]) > jm.limits.acceleration * (1 + 1e-6))
          return refused(fmt::format("at {:.3f} s joint {} would accelerate at {}, beyond its acceleration limit {}: "
                                     "give the points more time",
                                     t, jm.name, rate(model, j, std::abs(a[j]), 2),
                                     rate(model, j, jm.limits.acceleration, 2)));
      }
    }
  }

  SplinePlan plan;
  plan.target = pos.back();
  plan.motion.what = fmt::format("trajectory of {} points over {:.3f} s", request.points.size(), times.back());
  plan.motion.duration = times.back();
  plan.motion.sample = [spline](double t, std::vector<double>& q, std::vector<double>& qd, std::vector<double>& qdd) {
    spline->sample(t, q, qd, qdd);
  };
  return plan;
}

}  // namespace armctl::arm

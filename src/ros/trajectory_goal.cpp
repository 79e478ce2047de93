#include "ros/trajectory_goal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "core/quantity.hpp"

namespace armctl::ros_node {

namespace {

Error refused(GoalError code, std::string message) {
  return Error{ErrorKind::invalid_argument, std::move(message), code};
}

std::vector<std::string> names_of(const arm::ArmModel& model) {
  std::vector<std::string> out;
  for (const auto& j : model.joints) out.push_back(j.name);
  return out;
}

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

// "30.000 deg" / "120.000 mm", as the Arm API writes joint values (arm::format_joint_value).
std::string value(const arm::ArmModel& model, int joint, double si) {
  return format_quantity(model.joints[std::size_t(joint)].dimension, si);
}

// A joint rate as the Arm API writes it ("180 deg/s", "0.5 m/s^2"): per s (power 1) or per s^2 (2).
std::string rate(const arm::ArmModel& model, int joint, double si, int power) {
  return format_quantity(model.joints[std::size_t(joint)].dimension, si, power);
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

GoalRefusal refusal_of(const Error& e) {
  if (const auto* code = e.detail_as<GoalError>()) return {*code, e.message};
  return {GoalError::invalid_goal, e.message};
}

Result<std::vector<int>> map_joint_names(const arm::ArmModel& model, const std::vector<std::string>& names) {
  const auto allowed = fmt::format("{}", fmt::join(names_of(model), ", "));
  if (names.empty())
    return refused(GoalError::invalid_joints, fmt::format("the trajectory names no joints: arm {} has {} (the gripper "
                                                          "may be left out)", model.name, allowed));
  std::vector<int> out;
  std::vector<bool> seen(std::size_t(model.joint_count()), false);
  for (const auto& n : names) {
    // Exact names: ROS tools match them as strings (tf, robot_state_publisher).
    int index = -1;
    for (int j = 0; j < model.joint_count(); ++j)
      if (model.joints[std::size_t(j)].name == n) index = j;
    if (index < 0)
      return refused(GoalError::invalid_joints,
                     fmt::format("unknown joint '{}': arm {} has joints {}", n, model.name, allowed));
    if (seen[std::size_t(index)])
      return refused(GoalError::invalid_joints, fmt::format("joint '{}' is named twice in the trajectory", n));
    seen[std::size_t(index)] = true;
    out.push_back(index);
  }
  std::vector<std::string> missing;
  for (int j = 0; j < model.chain_joints(); ++j)
    if (!seen[std::size_t(j)]) missing.push_back(model.joints[std::size_t(j)].name);
  if (!missing.empty())
    return refused(GoalError::invalid_joints,
                   fmt::format("the trajectory leaves out joint(s) {}: every joint of arm {} must be in it ({}; the "
                               "gripper may be left out)", fmt::join(missing, ", "), model.name, allowed));
  return out;
}

Result<TrajectoryPlan> plan_trajectory(const arm::ArmModel& model, const std::vector<double>& from,
                                       const TrajectoryRequest& request, const StartTolerance& start) {
  auto joints = map_joint_names(model, request.joint_names);
  if (!joints) return joints.error();
  const std::size_t n = request.joint_names.size();
  const std::size_t all = std::size_t(model.joint_count());
  if (from.size() != all)
    return refused(GoalError::invalid_goal, fmt::format("the arm's positions are not known ({} values)", from.size()));
  if (request.points.empty()) return refused(GoalError::invalid_goal, "the trajectory has no points");

  // Sizes, finite values, times, position limits: each point as given.
  double previous_time = 0;
  bool velocities = true, accelerations = true;
  for (std::size_t k = 0; k < request.points.size(); ++k) {
    const auto& p = request.points[k];
    const std::string where = fmt::format("point {} (at {:.3f} s)", k, p.time);
    if (p.positions.size() != n)
      return refused(GoalError::invalid_goal, fmt::format("point {} has {} positions for {} joint names", k,
                                                          p.positions.size(), n));
    if (!p.velocities.empty() && p.velocities.size() != n)
      return refused(GoalError::invalid_goal, fmt::format("point {} has {} velocities for {} joint names (give none "
                                                          "or one per joint)", k, p.velocities.size(), n));
    if (!p.accelerations.empty() && p.accelerations.size() != n)
      return refused(GoalError::invalid_goal, fmt::format("point {} has {} accelerations for {} joint names (give "
                                                          "none or one per joint)", k, p.accelerations.size(), n));
    if (!p.effort.empty())
      return refused(GoalError::invalid_goal,
                     fmt::format("point {} gives efforts: armctl follows positions (and velocities, accelerations) "
                                 "only; leave effort empty", k));
    if (!std::isfinite(p.time))
      return refused(GoalError::invalid_goal, fmt::format("point {}: time_from_start is not finite", k));
    // As long as any armctl motion may be (the Python module's durations too): beyond, the
    // spline's polynomials lose their precision (found by fuzz_trajectory_goal).
    if (p.time > kLongestTrajectory)
      return refused(GoalError::invalid_goal,
                     fmt::format("point {}: time_from_start {:.3f} s is beyond the longest trajectory, {:.0f} s", k,
                                 p.time, kLongestTrajectory));
    if (p.time < 0)
      return refused(GoalError::invalid_goal,
                     fmt::format("{}: time_from_start is negative; times must be 0 or more and rising", where));
    if (k > 0 && p.time <= previous_time)
      return refused(GoalError::invalid_goal,
                     fmt::format("{}: times must rise from point to point, but point {} is at {:.3f} s", where, k - 1,
                                 previous_time));
    previous_time = p.time;
    velocities = velocities && !p.velocities.empty();
    accelerations = accelerations && !p.accelerations.empty();
    for (std::size_t i = 0; i < n; ++i) {
      const int j = (*joints)[i];
      const auto& jm = model.joints[std::size_t(j)];
      for (const auto* field : {&p.positions, &p.velocities, &p.accelerations})
        if (!field->empty() && !std::isfinite((*field)[i]))
          return refused(GoalError::invalid_goal, fmt::format("{}: joint {} has a value that is not finite", where,
                                                              jm.name));
      if (!jm.limits.contains(p.positions[i]))
        return refused(GoalError::invalid_goal,
                       fmt::format("{}: joint {} at {} is beyond its limits {}..{}", where, jm.name,
                                   value(model, j, p.positions[i]), value(model, j, jm.limits.lower),
                                   value(model, j, jm.limits.upper)));
    }
  }
  const auto& last = request.points.back();
  if (!last.velocities.empty())
    for (std::size_t i = 0; i < n; ++i)
      if (last.velocities[i] != 0)
        return refused(GoalError::invalid_goal,
                       fmt::format("the last point gives joint {} a velocity of {}: the arm ends a trajectory at "
                                   "rest, so the last velocities must be 0", model.joints[std::size_t((*joints)[i])].name,
                                   rate(model, (*joints)[i], last.velocities[i], 1)));

  // The knots: where the arm stands at 0 (a first point at 0 must be there), then the points.
  std::vector<double> times{0};
  std::vector<std::vector<double>> pos{from}, vel{std::vector<double>(all, 0.0)}, acc{std::vector<double>(all, 0.0)};
  std::size_t first = 0;
  if (request.points.front().time == 0) {
    const auto& p = request.points.front();
    for (std::size_t i = 0; i < n; ++i) {
      const int j = (*joints)[i];
      const bool angle = model.joints[std::size_t(j)].dimension == Dimension::angle;
      if (std::abs(p.positions[i] - from[std::size_t(j)]) > (angle ? start.angle : start.length))
        return refused(GoalError::invalid_goal,
                       fmt::format("point 0 is at 0 s, so it must be where the arm stands, but joint {} is at {} "
                                   "and point 0 puts it at {} (give the first point a time after 0 to move there)",
                                   model.joints[std::size_t(j)].name, value(model, j, from[std::size_t(j)]),
                                   value(model, j, p.positions[i])));
      if (!p.velocities.empty() && p.velocities[i] != 0)
        return refused(GoalError::invalid_goal, "point 0 is at 0 s, so its velocities must be 0 (the arm starts at rest)");
    }
    first = 1;
  }
  for (std::size_t k = first; k < request.points.size(); ++k) {
    const auto& p = request.points[k];
    std::vector<double> q = from, v(all, 0.0), a(all, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const auto j = std::size_t((*joints)[i]);
      q[j] = p.positions[i];
      if (velocities) v[j] = p.velocities[i];
      if (accelerations) a[j] = p.accelerations[i];
    }
    times.push_back(p.time);
    pos.push_back(q);
    vel.push_back(v);
    acc.push_back(a);
  }
  if (times.size() < 2)
    return refused(GoalError::invalid_goal, "the trajectory's only point is at 0 s, where the arm stands: nothing "
                                            "to do (give it a time after 0)");
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
        const int ji = int(j);
        const double slack = 1e-9;
        if (!jm.limits.contains(p[j], slack))
          return refused(GoalError::invalid_goal,
                         fmt::format("at {:.3f} s (on the way to point {}) joint {} would pass {}, beyond its limits "
                                     "{}..{}: add points or move them inside", t, k + first,
                                     jm.name, value(model, ji, p[j]), value(model, ji, jm.limits.lower),
                                     value(model, ji, jm.limits.upper)));
        if (std::abs(v[j]) > jm.limits.velocity * (1 + 1e-6))
          return refused(GoalError::invalid_goal,
                         fmt::format("at {:.3f} s joint {} would move at {}, beyond its velocity limit {}: give the "
                                     "points more time", t, jm.name, rate(model, ji, std::abs(v[j]), 1),
                                     rate(model, ji, jm.limits.velocity, 1)));
        if (std::abs(a[j]) > jm.limits.acceleration * (1 + 1e-6))
          return refused(GoalError::invalid_goal,
                         fmt::format("at {:.3f} s joint {} would accelerate at {}, beyond its acceleration limit {}: "
                                     "give the points more time", t, jm.name, rate(model, ji, std::abs(a[j]), 2),
                                     rate(model, ji, jm.limits.acceleration, 2)));
      }
    }
  }

  TrajectoryPlan plan;
  plan.joints = *joints;
  plan.target = pos.back();
  plan.motion.what = fmt::format("trajectory of {} points over {:.3f} s", request.points.size(), times.back());
  plan.motion.duration = times.back();
  plan.motion.sample = [spline](double t, std::vector<double>& q, std::vector<double>& qd, std::vector<double>& qdd) {
    spline->sample(t, q, qd, qdd);
  };
  return plan;
}

Result<GoalTolerances> map_tolerances(const arm::ArmModel& model, const std::vector<std::string>& names,
                                      const std::vector<JointTolerance>& path, const std::vector<JointTolerance>& goal,
                                      double goal_time) {
  // The names first (a tolerance may name any of them): every one a joint of the arm.
  if (auto known = map_joint_names(model, names); !known) return known.error();
  GoalTolerances out;
  out.path.assign(std::size_t(model.joint_count()), std::nullopt);
  out.goal = out.path;
  auto fill = [&](const std::vector<JointTolerance>& given, std::vector<std::optional<double>>& into,
                  const char* which) -> Status {
    for (const auto& t : given) {
      if (std::find(names.begin(), names.end(), t.name) == names.end())
        return refused(GoalError::invalid_joints,
                       fmt::format("{} tolerance for joint '{}', which is not a joint of the trajectory ({})", which,
                                   t.name, fmt::join(names, ", ")));
      if (std::isnan(t.position))
        return refused(GoalError::invalid_goal, fmt::format("{} tolerance of joint {} is NaN", which, t.name));
      // Exact names, as map_joint_names matched them (find_joint ignores case).
      const auto j = std::size_t(std::find_if(model.joints.begin(), model.joints.end(),
                                              [&](const arm::JointModel& m) { return m.name == t.name; }) -
                                 model.joints.begin());
      if (t.position > 0) into[j] = t.position;
      if (t.position < 0) into[j] = std::numeric_limits<double>::infinity();  // not checked
    }
    return Ok{};
  };
  if (auto s = fill(path, out.path, "path"); !s) return s.error();
  if (auto s = fill(goal, out.goal, "goal"); !s) return s.error();
  if (!std::isfinite(goal_time) || goal_time < 0)
    return refused(GoalError::invalid_goal,
                   fmt::format("goal_time_tolerance {} s is not allowed: 0 (the default) or more", goal_time));
  if (goal_time > 0) out.goal_time = goal_time;
  return out;
}

}  // namespace armctl::ros_node

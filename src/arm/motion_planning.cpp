#include "arm/motion_planning.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

namespace armctl::arm {

namespace {

Error refuse(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

Status check_joint_count(const ArmModel& model, const std::vector<double>& values, const char* what) {
  if (values.size() != std::size_t(model.joint_count()))
    return refuse(fmt::format("{} has {} joint values; arm '{}' has {} joints", what, values.size(), model.name,
                              model.joint_count()));
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      return refuse(fmt::format("{}: joint {} is not a finite number", what, model.joints[i].name));
  return Ok{};
}

Status within_limits(const ArmModel& model, std::size_t joint, double lowest, double highest, const char* what) {
  const JointLimits& l = model.joints[joint].limits;
  if (l.contains(lowest, 1e-9) && l.contains(highest, 1e-9)) return Ok{};
  const double outside = l.contains(lowest, 1e-9) ? highest : lowest;
  return refuse(fmt::format("{}: joint {} would reach {}, outside its limits {}..{}", what, model.joints[joint].name,
                            format_joint_value(model, int(joint), outside),
                            format_joint_value(model, int(joint), l.lower),
                            format_joint_value(model, int(joint), l.upper)));
}

}  // namespace

Result<std::vector<std::optional<double>>> joint_values_targets(const ArmModel& model,
                                                                const std::vector<files::JointValue>& values) {
  if (values.size() > model.joints.size())
    return refuse(fmt::format("{} joint values given; arm '{}' has {} joints", values.size(), model.name,
                              model.joints.size()));
  auto kind = [](Dimension d) { return d == Dimension::angle ? "an angle" : "a length"; };
  std::vector<std::optional<double>> targets(model.joints.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i].dimension != model.joints[i].dimension)
      return refuse(fmt::format("joint {} takes {}, not {}", model.joints[i].name, kind(model.joints[i].dimension),
                                kind(values[i].dimension)));
    targets[i] = values[i].value;
  }
  return targets;
}

Result<std::vector<double>> joint_values_target(const ArmModel& model, const std::vector<double>& from,
                                                const std::vector<files::JointValue>& values) {
  if (values.size() > from.size())
    return refuse(fmt::format("{} joint values given; arm '{}' has {} joints", values.size(), model.name, from.size()));
  auto targets = joint_values_targets(model, values);
  if (!targets) return targets.error();
  std::vector<double> target = from;
  for (std::size_t i = 0; i < target.size() && i < targets->size(); ++i)
    if ((*targets)[i]) target[i] = *(*targets)[i];
  return target;
}

Result<PlannedMotion> plan_joint_move(const ArmModel& model, const std::vector<double>& from, const JointMove& move) {
  const int n = model.joint_count();
  if (n < 1 || n > motion::kMaxTrajectoryJoints)
    return refuse(fmt::format("arm '{}' has {} joints; host-planned moves take 1..{}", model.name, n,
                              motion::kMaxTrajectoryJoints));
  if (auto ok = check_fraction_in(move.speed, "speed", motion::kMinSpeedFraction, motion::kMaxSpeedFraction); !ok)
    return ok.error();
  if (!(move.min_duration >= 0 && move.min_duration <= motion::kMaxMoveDuration))
    return refuse(fmt::format("duration {:g} s: allowed 0..{:g} s", move.min_duration, motion::kMaxMoveDuration));
  if (auto s = check_joint_count(model, from, "the start"); !s) return s.error();
  if (auto s = check_joint_count(model, move.target, "the target"); !s) return s.error();
  for (const auto& w : move.waypoints)
    if (auto s = check_joint_count(model, w, "a waypoint"); !s) return s.error();

  motion::TrajectoryInput in;
  in.joints = n;
  std::vector<motion::JointArray> waypoints(move.waypoints.size());
  for (int i = 0; i < n; ++i) {
    const std::size_t j = std::size_t(i);
    const JointLimits& l = model.joints[j].limits;
    in.position[j] = from[j];
    in.target_position[j] = move.target[j];
    in.max_velocity[j] = l.velocity * move.speed;
    in.max_acceleration[j] = l.acceleration;
    in.max_jerk[j] = l.jerk;
    for (std::size_t k = 0; k < waypoints.size(); ++k) waypoints[k][j] = move.waypoints[k][j];
  }
  in.waypoints = waypoints;
  in.min_duration = move.min_duration;
  auto trajectory = std::make_shared<motion::Trajectory>();
  if (auto s = motion::calculate_trajectory(in, *trajectory); !s) return s.error();
  // Between waypoints a joint may swing past them: the whole trajectory stays in the limits.
  const motion::TrajectoryExtrema x = trajectory->extrema();
  for (std::size_t j = 0; j < std::size_t(n); ++j)
    if (auto s = within_limits(model, j, x.min_position[j], x.max_position[j], "the move"); !s) return s.error();

  PlannedMotion m;
  m.what = "joint move";
  m.duration = trajectory->duration();
  m.sample = [trajectory, n](double t, std::vector<double>& p, std::vector<double>& v, std::vector<double>& a) {
    const motion::TrajectoryState s = trajectory->at(t);
    for (std::size_t j = 0; j < std::size_t(n); ++j) {
      p[j] = s.position[j];
      v[j] = s.velocity[j];
      a[j] = s.acceleration[j];
    }
  };
  return m;
}

Result<MoveDuration> joint_move_duration(const ArmModel& model, const std::vector<double>& from,
                                         const std::vector<double>& to, double requested_s, std::string_view as_given) {
  if (!(requested_s >= 0 && requested_s <= motion::kMaxMoveDuration))
    return refuse(fmt::format("{}: {:g} s is {}; allowed 0..{:g} s (0: as fast as the arm file's limits allow)",
                              as_given, requested_s,
                              std::isnan(requested_s) ? "not a number" : requested_s < 0 ? "negative" : "too long",
                              motion::kMaxMoveDuration));
  if (auto s = check_joint_count(model, from, "the start"); !s) return s.error();
  if (auto s = check_joint_count(model, to, "the target"); !s) return s.error();
  // A joint read back a hair past its limit (a servo's rounding; a joint without a target
  // stays there) still times the move.
  std::vector<double> start = from, target = to;
  for (std::size_t j = 0; j < start.size(); ++j) {
    start[j] = std::clamp(start[j], model.joints[j].limits.lower, model.joints[j].limits.upper);
    target[j] = std::clamp(target[j], model.joints[j].limits.lower, model.joints[j].limits.upper);
  }
  JointMove fastest;
  fastest.target = target;
  fastest.speed = 1;
  auto planned = plan_joint_move(model, start, fastest);
  if (!planned) return planned.error();
  MoveDuration out;
  out.shortest = planned->duration;
  out.seconds = std::max(requested_s, out.shortest);
  // Within a microsecond of the shortest is not worth a note (a duration read back).
  out.stretched = requested_s < out.shortest - 1e-6;
  if (!out.stretched) return out;
  // The joint that needs the longest alone at its limits names the reason.
  std::size_t slowest = 0;
  double longest = -1;
  for (std::size_t j = 0; j < to.size(); ++j) {
    const JointLimits& l = model.joints[j].limits;
    const double t = std::abs(to[j] - from[j]) / l.velocity;
    if (t > longest) {
      longest = t;
      slowest = j;
    }
  }
  const JointModel& jm = model.joints[slowest];
  out.note = fmt::format("{} is too short for joint {} to move {} within its limits ({}): the move takes {:.2f} s",
                         as_given, jm.name, format_quantity(jm.dimension, std::abs(to[slowest] - from[slowest])),
                         format_quantity(jm.dimension, jm.limits.velocity, 1), out.seconds);
  return out;
}

double tool_quantization(const ArmModel& model, Protocol protocol, const std::vector<double>& q) {
  motion::JointVector chain(model.chain_joints());
  for (int i = 0; i < model.chain_joints(); ++i) chain[i] = q[std::size_t(i)];
  const motion::Jacobian j = model.kinematics->jacobian(chain);
  double limit = 0;
  for (int i = 0; i < model.chain_joints(); ++i) {
    const auto& map = model.joints[std::size_t(i)].map(protocol);
    if (!map) continue;
    limit += 0.5 / std::abs(map->device_per_unit()) * j.block<3, 1>(0, i).norm();
  }
  return limit;
}

std::vector<motion::PathLimits> path_limits(const ArmModel& model) {
  std::vector<motion::PathLimits> out;
  for (int i = 0; i < model.chain_joints(); ++i) {
    const JointModel& j = model.joints[std::size_t(i)];
    out.push_back({j.limits.lower, j.limits.upper, j.limits.velocity, j.limits.acceleration, j.name, j.dimension});
  }
  return out;
}

namespace {

// One stretch of the path between two rests, timed rest to rest along s.
struct Run {
  double s0 = 0, s1 = 0;  // nominal s
  double t0 = 0;          // executor time of its start
  motion::Trajectory timing;
};

// The limits of ds/dt, d2s/dt2 and d3s/dt3 on one run: the tool's own (speed 1 = as
// programmed, the path's accelerations over the fastest segment's speed), and the joints':
// |dq/ds| ds/dt <= v, |d2q/ds2| (ds/dt)^2 + |dq/ds| d2s/dt2 <= a (half of a each at most), and
// |dq/ds| d3s/dt3 <= jerk / 2. Conservative over the whole run: the slowest point of a run
// sets its speed (docs/motion.md).
motion::JerkLimits run_limits(const ArmModel& model, const motion::CartesianPath& path,
                              const motion::CheckedPath& checked, double s0, double s1, const PathTiming& timing) {
  double rate = 1, fastest = 0, fastest_turn = 0;
  for (const auto& seg : path.segments())
    if (seg.end_s > s0 && seg.start_s < s1) {
      fastest = std::max(fastest, seg.speed);
      fastest_turn = std::max(fastest_turn, seg.angular_speed);
    }
  double accel = std::min(fastest > 0 ? timing.acceleration / fastest : 1e9,
                          fastest_turn > 0 ? timing.angular_acceleration / fastest_turn : 1e9);
  const int chain = model.chain_joints();
  std::vector<double> qs(std::size_t(chain), 0.0), qss(std::size_t(chain), 0.0);
  for (std::size_t k = 0; k < checked.s.size(); ++k) {
    if (checked.s[k] < s0 - 1e-12 || checked.s[k] > s1 + 1e-12) continue;
    rate = std::min(rate, checked.rate_limit[k]);
    for (int i = 0; i < chain; ++i) {
      qs[std::size_t(i)] = std::max(qs[std::size_t(i)], std::abs(checked.dq_ds[k][i]));
      qss[std::size_t(i)] = std::max(qss[std::size_t(i)], std::abs(checked.d2q_ds2[k][i]));
    }
  }
  double jerk = accel / 0.1;  // the tool's acceleration builds up over 0.1 s
  for (int i = 0; i < chain; ++i) {
    const JointLimits& l = model.joints[std::size_t(i)].limits;
    const std::size_t j = std::size_t(i);
    if (qss[j] > 0) rate = std::min(rate, std::sqrt(0.5 * l.acceleration / qss[j]));
    if (qs[j] > 0) {
      accel = std::min(accel, (l.acceleration - qss[j] * rate * rate) / qs[j]);
      jerk = std::min(jerk, 0.5 * l.jerk / qs[j]);
    }
  }
  return motion::JerkLimits{rate, accel, jerk};
}

}  // namespace

Result<PathPlan> plan_path(const ArmModel& model, const std::vector<double>& from,
                           std::span<const motion::PathSegment> segments, const PathTiming& timing) {
  return plan_path(ArmKinematics(model), from, segments, timing);
}

Result<PathPlan> plan_path(const ArmKinematics& kinematics, const std::vector<double>& from,
                           std::span<const motion::PathSegment> segments, const PathTiming& timing) {
  const ArmModel& model = kinematics.model();
  if (auto s = check_joint_count(model, from, "the start"); !s) return s.error();
  if (!(timing.acceleration > 0) || !(timing.angular_acceleration > 0) || !std::isfinite(timing.acceleration) ||
      !std::isfinite(timing.angular_acceleration))
    return refuse("path accelerations must be finite and above 0");
  if (segments.empty()) return refuse("the path has no segments");
  // A point beyond any reach, and a speed outside what a request may ask, are refused here,
  // before the path is built and sampled (the apps check speeds in their users' words
  // first; this holds for every caller).
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const motion::PathSegment& seg = segments[i];
    auto fail = [&](const Error& e) {
      motion::PathRefusal r;
      r.segment = int(i);
      r.kind = seg.kind;
      r.reason = e.message;
      return motion::path_refusal(std::move(r));
    };
    if (auto ok = check_quantity_in(seg.speed, Dimension::length, "speed", 1, motion::kMinToolSpeed,
                                    motion::kMaxToolSpeed);
        !ok)
      return fail(ok.error());
    if (auto ok = check_quantity_in(seg.angular_speed, Dimension::angle, "angular speed", 1,
                                    motion::kMinToolAngularSpeed, motion::kMaxToolAngularSpeed);
        !ok)
      return fail(ok.error());
    if (auto ok = within_reach(model, seg.target.position, "target"); !ok) return fail(ok.error());
    if (seg.kind == motion::SegmentKind::circ)
      if (auto ok = within_reach(model, seg.via, "via point"); !ok) return fail(ok.error());
  }
  const int chain = model.chain_joints();
  motion::JointVector start(chain);
  for (int i = 0; i < chain; ++i) start[i] = from[std::size_t(i)];
  const motion::Pose start_pose = kinematics.forward(start);  // the tool's pose, tool frame included

  auto path = motion::build_cartesian_path(start_pose, segments);
  if (!path) return path.error();
  const auto limits = path_limits(model);
  auto checked = motion::check_path(*path, *model.kinematics, model.tool, start, limits,
                                    kinematics.reaches_nearest_orientation());
  if (!checked) return checked.error();

  PathPlan plan;
  plan.path = std::make_shared<const motion::CartesianPath>(std::move(path).value());
  plan.checked = std::make_shared<const motion::CheckedPath>(std::move(checked).value());

  auto runs = std::make_shared<std::vector<Run>>();
  double s0 = 0, t = 0;
  for (double rest : plan.path->rests()) {
    if (rest <= s0 + 1e-12) continue;
    Run run;
    run.s0 = s0;
    run.s1 = rest;
    run.t0 = t;
    const motion::JerkLimits l = run_limits(model, *plan.path, *plan.checked, s0, rest, timing);
    if (!(l.velocity > 0) || !(l.acceleration > 0) || !(l.jerk > 0))
      return refuse(fmt::format("the path cannot be timed between nominal {:.3f} s and {:.3f} s: the joints' "
                                "acceleration limits leave nothing to move with",
                                s0, rest));
    motion::TrajectoryInput in;
    in.joints = 1;
    in.position[0] = s0;
    in.target_position[0] = rest;
    in.max_velocity[0] = l.velocity;
    in.max_acceleration[0] = l.acceleration;
    in.max_jerk[0] = l.jerk;
    if (auto s = motion::calculate_trajectory(in, run.timing); !s) return s.error();
    t += run.timing.duration();
    runs->push_back(std::move(run));
    s0 = rest;
  }

  PlannedMotion& m = plan.motion;
  const auto& first = segments.front();
  m.what = fmt::format("{} path of {} segment{}", motion::to_string(first.kind), segments.size(),
                       segments.size() == 1 ? "" : "s");
  m.duration = t;
  auto checked_ptr = plan.checked;
  const std::vector<double> rest_of_arm = from;
  m.sample = [runs, checked_ptr, rest_of_arm, chain](double time, std::vector<double>& p,
                                                                 std::vector<double>& v, std::vector<double>& a) {
    std::size_t k = 0;
    while (k + 1 < runs->size() && time >= (*runs)[k + 1].t0) ++k;
    const Run& run = (*runs)[k];
    const motion::TrajectoryState st = run.timing.at(time - run.t0);
    const double s = st.position[0], sd = st.velocity[0], sdd = st.acceleration[0];
    const motion::CheckedPath::Joints q = checked_ptr->joints_with_rates(std::clamp(s, run.s0, run.s1));
    for (std::size_t j = 0; j < p.size(); ++j) {
      if (int(j) >= chain) {
        p[j] = rest_of_arm[j];
        v[j] = a[j] = 0;
        continue;
      }
      const int i = int(j);
      p[j] = q.position[i];
      v[j] = q.dq_ds[i] * sd;
      a[j] = q.d2q_ds2[i] * sd * sd + q.dq_ds[i] * sdd;
    }
  };
  return plan;
}

namespace {

// The 5-joint xArm's tool pitch at a line's target when the move asks none: free, as for a
// PTP to a position alone, and chosen the same way (ArmKinematics::inverse): the pitch the line
// starts with if the target reaches with it (the line then keeps it exactly,
// docs/paths.md), else the middle of the widest run of pitches that reach it. `near`
// (every joint): the arm before the target; set to the target's solution.
// Nothing reaches: the pitch as it was, for the path check to refuse with its reason.
double line_target_pitch(const ArmKinematics& arm, const CartesianGoal& goal, const motion::Rpy& rpy,
                         std::vector<double>& near) {
  CartesianGoal position_alone = goal;
  position_alone.roll = rpy.roll;
  position_alone.pitch.reset();
  position_alone.yaw.reset();  // follows the position
  auto solutions = arm.inverse(position_alone, near);
  if (!solutions) return rpy.pitch;
  const motion::JointVector& q = solutions->front().joints;
  for (int i = 0; i < q.size(); ++i) near[std::size_t(i)] = q[i];
  return arm.tool_rpy(arm.forward(q), q).pitch;
}

}  // namespace

std::vector<motion::PathSegment> path_segments(const ArmKinematics& arm, const std::vector<double>& from,
                                               std::span<const CartesianMove> moves) {
  const motion::JointVector q = arm.chain_of(from);
  motion::Rpy current = arm.tool_rpy(arm.forward(q), q);
  std::vector<double> near = from;
  const bool free_pitch = arm.pitch_free();
  std::vector<motion::PathSegment> segments;
  segments.reserve(moves.size());
  for (const CartesianMove& m : moves) {
    current = arm.goal_rpy(m.goal, current);
    if (free_pitch && !m.goal.pitch) current.pitch = line_target_pitch(arm, m.goal, current, near);
    motion::PathSegment seg;
    seg.kind = m.kind;
    seg.target.position = m.goal.position;
    seg.target.orientation = motion::from_rpy(current);
    seg.via = m.via;
    seg.speed = m.speed;
    seg.angular_speed = m.angular_speed;
    seg.zone = m.zone;
    segments.push_back(seg);
  }
  return segments;
}

}  // namespace armctl::arm

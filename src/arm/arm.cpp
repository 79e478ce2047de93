#include "arm/arm.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "arm/motion_planning.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"

namespace armctl::arm {

namespace {

Error refuse(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

// Rest-to-rest time of a trapezoidal (or triangular) profile over `distance`.
double profile_seconds(double distance, double v, double a) {
  if (distance <= 0) return 0;
  const double ramp = v / a;                 // time to reach v
  if (distance <= v * ramp) return 2 * std::sqrt(distance / a);  // never reaches v
  return distance / v + ramp;
}

motion::JointVector chain_part(const ArmModel& m, const std::vector<double>& q) {
  motion::JointVector v(m.chain_joints());
  for (int i = 0; i < m.chain_joints(); ++i) v[i] = q[std::size_t(i)];
  return v;
}

motion::Pose compose(const motion::Pose& a, const motion::Pose& b) {
  motion::Pose out;
  out.position = a.position + a.orientation * b.position;
  out.orientation = (a.orientation * b.orientation).normalized();
  return out;
}

double wrap(double a) { return std::remainder(a, 2 * std::numbers::pi); }  // into -pi..pi

motion::Pose inverse_of(const motion::Pose& p) {
  motion::Pose out;
  out.orientation = p.orientation.conjugate();
  out.position = -(out.orientation * p.position);
  return out;
}

}  // namespace

std::string format_joint_value(const ArmModel& model, int index, double si) {
  return format_quantity(model.joints[std::size_t(index)].dimension, si);
}

Arm::Arm(ArmModel model, std::unique_ptr<ArmDevice> device)
    : model_(std::move(model)), device_(std::move(device)) {
  if (!model_.supports(device_->protocol()))
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("arm '{}' has no {} mapping for its joints, so {} cannot drive it", model_.name,
                                  to_string(device_->protocol()), device_->description()));
}

Result<JointState> Arm::read() {
  auto raw = device_->read_positions();
  if (!raw) return raw.error();
  JointState s;
  s.time = device_->clock().now();
  s.device = *raw;
  s.positions = model_.from_device(device_->protocol(), s.device);
  return s;
}

motion::JointVector Arm::chain_of(const std::vector<double>& positions) const {
  return armctl::arm::chain_part(model_, positions);
}

motion::Pose Arm::forward(const motion::JointVector& chain) const {
  return compose(model_.kinematics->forward(chain), model_.tool);
}

Result<motion::Pose> Arm::pose() {
  auto s = read();
  if (!s) return s.error();
  return forward(chain_part(model_, s->positions));
}

Status Arm::check_targets(const std::vector<std::optional<double>>& targets) const {
  if (targets.size() != model_.joints.size())
    return refuse(fmt::format("{} targets given for an arm with {} joints", targets.size(), model_.joints.size()));
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!targets[i]) continue;
    const JointModel& j = model_.joints[i];
    const double q = *targets[i];
    if (!std::isfinite(q)) return refuse(fmt::format("joint {}: the target is not a finite number", j.name));
    if (!j.limits.contains(q, 1e-9))
      return refuse(fmt::format("joint {}: target {} is outside its limits {}..{}", j.name,
                                format_quantity(j.dimension, q), format_quantity(j.dimension, j.limits.lower),
                                format_quantity(j.dimension, j.limits.upper)));
  }
  return Ok{};
}

Duration Arm::move_time(const std::vector<double>& from, const std::vector<std::optional<double>>& to,
                        double speed) const {
  double seconds = 0;
  for (std::size_t i = 0; i < to.size(); ++i) {
    if (!to[i]) continue;
    const JointLimits& l = model_.joints[i].limits;
    seconds = std::max(seconds, profile_seconds(std::abs(*to[i] - from[i]), speed * l.velocity, l.acceleration));
  }
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(seconds));
}

Status Arm::move_joints(const std::vector<std::optional<double>>& targets, const MoveOptions& options) {
  if (auto ok = check_targets(targets); !ok) return ok;
  if (!options.duration)
    if (auto ok = check_fraction_in(options.speed, "speed (of the joints' velocity limits)", motion::kMinSpeedFraction,
                                    motion::kMaxSpeedFraction);
        !ok)
      return ok;
  if (options.duration && options.duration->count() < 0) return refuse("a move's duration cannot be negative");
  auto now = read();
  if (!now) return now.error();
  // Joints without a target keep where they are; a coupled joint's partner must be sent too
  // (its actuator value depends on both), at the position it has now.
  std::vector<double> full = now->positions;
  std::vector<std::optional<double>> with_partners = targets;
  for (const Coupling& c : model_.couplings) {
    if (!targets[std::size_t(c.first)] && !targets[std::size_t(c.second)]) continue;
    for (int k : {c.first, c.second})
      if (!with_partners[std::size_t(k)]) with_partners[std::size_t(k)] = now->positions[std::size_t(k)];
  }
  for (std::size_t i = 0; i < full.size(); ++i)
    if (with_partners[i]) full[i] = *with_partners[i];
  const std::vector<double> device = model_.to_device(device_->protocol(), full);
  const DeviceRange range = device_range(device_->protocol());
  std::vector<std::optional<double>> device_targets(device.size());
  for (std::size_t i = 0; i < device.size(); ++i) {
    if (!with_partners[i]) continue;
    if (device[i] < range.min - 0.5 || device[i] > range.max + 0.5)
      return refuse(fmt::format("joint {}: {} maps to device position {:.0f}, outside what {} carries ({}..{}); "
                                "check the arm file's mapping",
                                model_.joints[i].name, format_joint_value(model_, int(i), full[i]), device[i],
                                to_string(device_->protocol()), range.min, range.max));
    device_targets[i] = device[i];
  }
  Duration duration{};
  if (options.duration) {
    auto timed = joint_move_duration(model_, now->positions, full, std::chrono::duration<double>(*options.duration).count(),
                                     options.duration_words);
    if (!timed) return timed.error();
    if (timed->stretched && options.on_note) options.on_note(timed->note);
    duration = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(timed->seconds));
  } else {
    duration = move_time(now->positions, with_partners, options.speed);
  }
  if (auto sent = device_->move(device_targets, duration); !sent) return sent;
  last_targets_ = with_partners;
  return Ok{};
}

motion::Rpy Arm::tool_rpy(const motion::Pose& pose, const motion::JointVector& chain) const {
  motion::Rpy rpy = motion::to_rpy(pose.orientation);
  if (model_.family != motion::KinematicFamily::xarm) return rpy;
  // Every orientation has two roll-pitch-yaw forms: (r, p, y) and (r + pi, pi - p, y + pi).
  // The 5-joint arm's own is the one whose yaw is where the arm points (its base angle):
  // then roll is the wrist's roll and pitch the tool's tilt, free to exceed 90 deg.
  const motion::Rpy other{wrap(rpy.roll + std::numbers::pi), wrap(std::numbers::pi - rpy.pitch),
                          wrap(rpy.yaw + std::numbers::pi)};
  const double pointing = chain[0];
  return std::abs(wrap(other.yaw - pointing)) < std::abs(wrap(rpy.yaw - pointing)) ? other : rpy;
}

motion::Rpy Arm::goal_rpy(const CartesianGoal& goal, const motion::Rpy& current) const {
  motion::Rpy rpy{goal.roll.value_or(current.roll), goal.pitch.value_or(current.pitch),
                  goal.yaw.value_or(current.yaw)};
  // The 5-joint arm's yaw is where it points: left open, it follows the position.
  if (model_.family == motion::KinematicFamily::xarm && !goal.yaw)
    rpy.yaw = std::atan2(goal.position.y(), goal.position.x());
  return rpy;
}

Result<std::vector<motion::IkSolution>> Arm::inverse(const CartesianGoal& goal, const JointState& now) const {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(goal.position[k])) return refuse("the tool position is not a finite number");
  if (auto ok = within_reach(model_, goal.position, "the tool target"); !ok) return ok.error();
  for (const auto& a : {goal.roll, goal.pitch, goal.yaw})
    if (a && !std::isfinite(*a)) return refuse("the tool orientation is not a finite number");
  const motion::JointVector near = chain_part(model_, now.positions);
  const motion::Rpy rpy = goal_rpy(goal, tool_rpy(forward(near), near));
  motion::IkRequest request;
  request.nearest_orientation = goal.nearest_orientation;
  if (model_.family == motion::KinematicFamily::xarm && !goal.yaw) request.nearest_orientation = true;
  auto solve = [&](const motion::Rpy& o) {
    motion::Pose tool_pose;
    tool_pose.position = goal.position;
    tool_pose.orientation = motion::from_rpy(o);
    request.target = compose(tool_pose, inverse_of(model_.tool));  // where the tool link must be
    return model_.kinematics->inverse(request, near);
  };
  auto solutions = solve(rpy);
  if (!solutions && !goal.pitch && model_.family == motion::KinematicFamily::xarm) {
    // Only a position asked of the 5-joint arm: the tool's pitch is free. Keep the current
    // one if it reaches; else look at every whole degree from it: the pitches that reach
    // form runs, and the middle of the widest run is taken (the nearer of two as wide). Not
    // the nearest pitch that reaches: it lies on the edge of its run (a joint at its limit),
    // and its run may be a sliver (from the straight-up start, x 150 y 50 z 120 mm reaches
    // at -106..-103 deg and at 15..70 deg), so that a line starting or ending there leaves
    // what the arm reaches within millimetres ("beyond reach by 0.0 mm at this tool pitch").
    struct Run {
      int from = 0, to = 0;  // degrees from the current pitch
      int width() const { return to - from; }
      int distance() const { return std::min(std::abs(from), std::abs(to)); }
    };
    std::vector<Run> runs;
    for (int k = -180; k <= 180; ++k) {
      motion::Rpy o = rpy;
      o.pitch = rpy.pitch + k * std::numbers::pi / 180;
      if (!solve(o)) continue;
      if (!runs.empty() && runs.back().to == k - 1)
        runs.back().to = k;
      else
        runs.push_back({k, k});
    }
    if (runs.empty()) return solve(rpy).error();
    const Run* widest = &runs.front();
    for (const Run& r : runs)
      if (r.width() > widest->width() || (r.width() == widest->width() && r.distance() < widest->distance()))
        widest = &r;
    motion::Rpy o = rpy;
    o.pitch = rpy.pitch + (widest->from + widest->to) / 2 * std::numbers::pi / 180;
    solutions = solve(o);
  }
  if (!solutions) return solutions;
  if (!goal.elbow) return solutions;
  std::vector<motion::IkSolution> kept;
  for (const auto& s : *solutions)
    if (s.configuration.elbow == goal.elbow) kept.push_back(s);
  if (kept.empty())
    return refuse(fmt::format("the pose is reachable, but not with the elbow {} (within the joint limits)",
                              motion::to_string(*goal.elbow)));
  return kept;
}

Status Arm::move_to(const CartesianGoal& goal, const MoveOptions& options) {
  auto now = read();
  if (!now) return now.error();
  auto solutions = inverse(goal, *now);
  if (!solutions) return solutions.error();
  const motion::IkSolution& best = solutions->front();
  std::vector<std::optional<double>> targets(model_.joints.size());
  for (int i = 0; i < model_.chain_joints(); ++i) targets[std::size_t(i)] = best.joints[i];
  return move_joints(targets, options);
}

Status Arm::gripper(double closed_fraction, const MoveOptions& options) {
  if (!model_.gripper) return Error{ErrorKind::unsupported, fmt::format("arm '{}' has no gripper", model_.name)};
  if (!std::isfinite(closed_fraction) || closed_fraction < 0 || closed_fraction > 1)
    return refuse(fmt::format("gripper: {} is outside 0..1 (0 = open, 1 = closed)", closed_fraction));
  std::vector<std::optional<double>> targets(model_.joints.size());
  targets[std::size_t(model_.gripper->joint)] = model_.gripper->at(closed_fraction);
  return move_joints(targets, options);
}

Result<JointState> Arm::wait(const WaitOptions& options) {
  const TimePoint deadline = device_->clock().now() + options.timeout;
  std::optional<JointState> previous;
  for (;;) {
    auto s = read();
    if (!s) return s.error();
    if (options.on_read) options.on_read(*s);
    std::string late;
    bool resting = previous.has_value();
    for (std::size_t i = 0; i < last_targets_.size(); ++i) {
      if (!last_targets_[i]) continue;
      const JointModel& j = model_.joints[i];
      const double asked = i < options.joint_tolerance.size() && options.joint_tolerance[i] > 0
                               ? options.joint_tolerance[i]
                               : j.dimension == Dimension::angle ? options.angle_tolerance : options.length_tolerance;
      // A joint can be no nearer its target than half a unit of its device (through the arm
      // controller a SCARA joint's unit is 1.42 deg).
      const auto& map = j.map(device_->protocol());
      const double half_unit = map ? 0.5 / std::abs(map->device_per_unit()) : 0.0;
      const double tol = std::max(asked, half_unit * 1.01);
      if (previous && std::abs(s->positions[i] - previous->positions[i]) > asked / 4) resting = false;
      if (std::abs(s->positions[i] - *last_targets_[i]) <= tol) continue;
      late += fmt::format("{}{} at {} (target {})", late.empty() ? "" : "; ", j.name,
                          format_quantity(j.dimension, s->positions[i]), format_quantity(j.dimension, *last_targets_[i]));
    }
    if (late.empty() && resting) return s;
    if (late.empty() && device_->clock().now() >= deadline) return s;  // there, if still creeping
    previous = *s;
    if (device_->clock().now() >= deadline)
      return Error{ErrorKind::timeout,
                   fmt::format("not arrived after {:.1f} s: {}", std::chrono::duration<double>(options.timeout).count(), late)};
    if (options.interrupted && options.interrupted()) return Error{ErrorKind::device, "wait interrupted"};
    if (auto idled = device_->idle(options.poll.value_or(device_->poll_interval())); !idled) return idled.error();
  }
}

Status Arm::stop() {
  last_targets_.clear();
  return device_->stop();
}

Status Arm::set_torque(bool on) {
  last_targets_.clear();
  return device_->set_torque(on);
}

}  // namespace armctl::arm

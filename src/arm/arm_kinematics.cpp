#include "arm/arm_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "arm/collision_shapes.hpp"
#include "core/quantity.hpp"

namespace armctl::arm {

namespace {

Error refuse(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

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

namespace {

// The arm's side of its collision world, from its model (arm/arm_model.hpp). `self`: its
// links against each other too (but the pairs its file allows).
scene::ArmBodies arm_bodies(const ArmModel& m, bool self = true) {
  scene::ArmBodies a;
  a.links = m.bodies;
  a.allowed = m.allowed_collisions;
  if (!self)
    for (const auto& x : m.bodies->bodies)
      for (const auto& y : m.bodies->bodies) a.allowed.emplace_back(x.name, y.name);
  a.tool_link = m.tool_link;
  a.tool_frame.linear() = m.tool.orientation.toRotationMatrix();
  a.tool_frame.translation() = m.tool.position;
  for (const auto& j : m.joints) a.joint_reach.push_back(std::max(std::abs(j.limits.lower), std::abs(j.limits.upper)));
  return a;
}

}  // namespace

ArmKinematics::ArmKinematics(ArmModel model, std::optional<Protocol> device)
    : model_(std::move(model)), device_(device) {
  // The arm file's names, fence and reduced mode were checked when it was read: install
  // cannot fail for a model that parse_arm_model made.
  if (has_collision_shapes(model_))
    if (auto ok = install(scene::Scene{}); !ok) throw ArmctlError(ok.error());
}

scene::Scene with_arm_limits(scene::Scene scene, const ArmModel& model) {
  if (!scene.fence) scene.fence = model.fence;
  if (!scene.reduced) scene.reduced = model.reduced;
  return scene;
}

namespace {
Status check_shapes(const ArmModel& m) {
  if (has_collision_shapes(m)) return Ok{};
  return Error{ErrorKind::invalid_config,
               fmt::format("arm '{}': its URDF ({}) gives no link a <collision> shape, so a scene cannot be checked",
                           m.name, m.urdf.string())};
}
}  // namespace

Result<std::shared_ptr<const scene::CollisionWorld>> scene_only_world(const ArmModel& model, scene::Scene scene) {
  if (auto ok = check_shapes(model); !ok) return ok.error();
  // The fence and reduced mode are armctl's rules, not walls: a simulated arm passes them.
  scene.fence.reset();
  scene.reduced.reset();
  return scene::CollisionWorld::build(arm_bodies(model, false), std::move(scene));
}

Result<std::shared_ptr<const ArmKinematics>> ArmKinematics::with_scene(scene::Scene scene) const {
  if (auto ok = check_shapes(model_); !ok) return ok.error();
  auto out = std::make_shared<ArmKinematics>(*this);
  if (auto ok = out->install(std::move(scene)); !ok) return ok.error();
  return std::shared_ptr<const ArmKinematics>(std::move(out));
}

Status ArmKinematics::install(scene::Scene scene) {
  scene = with_arm_limits(std::move(scene), model_);
  scene::ArmBodies bodies = arm_bodies(model_);
  std::optional<ReducedLimits> reduced;
  if (scene.reduced) {
    // Checked whether on or off: switching it on later must not fail.
    auto limits = reduced_limits(model_, *scene.reduced);
    if (!limits) return scene.file.empty() ? limits.error() : limits.error().prefixed(scene.file.string() + ": ");
    if (scene.reduced->on) {
      bodies.joint_ranges = limits->joint_ranges;
      reduced = std::move(limits).value();
    }
  }
  auto world = scene::CollisionWorld::build(std::move(bodies), std::move(scene));
  if (!world) return world.error();
  collisions_ = std::move(world).value();
  reduced_ = std::move(reduced);
  return Ok{};
}

motion::JointVector ArmKinematics::chain_of(const std::vector<double>& positions) const {
  motion::JointVector v(model_.chain_joints());
  for (int i = 0; i < model_.chain_joints(); ++i) v[i] = positions[std::size_t(i)];
  return v;
}

motion::Pose ArmKinematics::forward(const motion::JointVector& chain) const {
  return compose(model_.kinematics->forward(chain), model_.tool);
}

motion::Rpy ArmKinematics::tool_rpy(const motion::Pose& pose, const motion::JointVector& chain) const {
  motion::Rpy rpy = motion::to_rpy(pose.orientation);
  if (!yaw_follows_position()) return rpy;
  // Every orientation has two roll-pitch-yaw forms: (r, p, y) and (r + pi, pi - p, y + pi).
  // The 5-joint arm's own is the one whose yaw is where the arm points (its base angle):
  // then roll is the wrist's roll and pitch the tool's tilt, free to exceed 90 deg.
  const motion::Rpy other{wrap(rpy.roll + std::numbers::pi), wrap(std::numbers::pi - rpy.pitch),
                          wrap(rpy.yaw + std::numbers::pi)};
  const double pointing = chain[0];
  return std::abs(wrap(other.yaw - pointing)) < std::abs(wrap(rpy.yaw - pointing)) ? other : rpy;
}

motion::Rpy ArmKinematics::tool_rpy_at(const std::vector<double>& positions) const {
  const motion::JointVector q = chain_of(positions);
  return tool_rpy(forward(q), q);
}

motion::Rpy ArmKinematics::goal_rpy(const CartesianGoal& goal, const motion::Rpy& current) const {
  motion::Rpy rpy{goal.roll.value_or(current.roll), goal.pitch.value_or(current.pitch),
                  goal.yaw.value_or(current.yaw)};
  // The 5-joint arm's yaw is where it points: left open, it follows the position.
  if (yaw_follows_position() && !goal.yaw) rpy.yaw = std::atan2(goal.position.y(), goal.position.x());
  return rpy;
}

CartesianGoal ArmKinematics::keeping_orientation(const Eigen::Vector3d& position, const motion::Rpy& current) const {
  CartesianGoal goal;
  goal.position = position;
  goal.roll = current.roll;
  goal.pitch = current.pitch;
  if (!yaw_follows_position()) goal.yaw = current.yaw;
  return goal;
}

Result<std::vector<motion::IkSolution>> ArmKinematics::inverse(const CartesianGoal& goal,
                                                               const std::vector<double>& near_positions) const {
  if (near_positions.size() != std::size_t(model_.joint_count()))
    return refuse(fmt::format("{} joint values given to start from; arm '{}' has {} joints", near_positions.size(),
                              model_.name, model_.joint_count()));
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(goal.position[k])) return refuse("the tool position is not a finite number");
  if (auto ok = within_reach(model_, goal.position, "the tool target"); !ok) return ok.error();
  for (const auto& a : {goal.roll, goal.pitch, goal.yaw})
    if (a && !std::isfinite(*a)) return refuse("the tool orientation is not a finite number");
  const motion::JointVector near = chain_of(near_positions);
  const motion::Rpy rpy = goal_rpy(goal, tool_rpy(forward(near), near));
  motion::IkRequest request;
  request.nearest_orientation = goal.nearest_orientation;
  if (reaches_nearest_orientation() && !goal.yaw) request.nearest_orientation = true;
  auto solve = [&](const motion::Rpy& o) {
    motion::Pose tool_pose;
    tool_pose.position = goal.position;
    tool_pose.orientation = motion::from_rpy(o);
    request.target = compose(tool_pose, inverse_of(model_.tool));  // where the tool link must be
    return model_.kinematics->inverse(request, near);
  };
  auto solutions = solve(rpy);
  if (!solutions && !goal.pitch && pitch_free()) {
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

Result<std::vector<double>> ArmKinematics::nearest_joints(const CartesianGoal& goal,
                                                          const std::vector<double>& near) const {
  auto solutions = inverse(goal, near);
  if (!solutions) return solutions.error();
  std::vector<double> target = near;
  const motion::JointVector& q = solutions->front().joints;
  for (int i = 0; i < q.size(); ++i) target[std::size_t(i)] = q[i];
  return target;
}

Status ArmKinematics::check_targets(const std::vector<std::optional<double>>& targets,
                                    const std::vector<double>* from) const {
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
  if (!device_) return Ok{};
  // The device's range: every joint whose device value is known (a coupled joint's depends
  // on its partner too, given or where `from` has it).
  std::vector<double> full(targets.size(), 0.0);
  std::vector<bool> sent(targets.size(), false);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (targets[i]) full[i] = *targets[i];
    else if (from && from->size() == targets.size()) full[i] = (*from)[i];
    else full[i] = std::clamp(0.0, model_.joints[i].limits.lower, model_.joints[i].limits.upper);
    sent[i] = targets[i].has_value();
  }
  for (const Coupling& c : model_.couplings) {
    const auto a = std::size_t(c.first), b = std::size_t(c.second);
    const bool known = (targets[a] || (from && from->size() == targets.size())) &&
                       (targets[b] || (from && from->size() == targets.size()));
    if (!known) sent[a] = sent[b] = false;  // its device value is not known without its partner
  }
  auto device = device_targets(full, sent);
  if (!device) return device.error();
  return Ok{};
}

Status ArmKinematics::check_targets(const std::vector<double>& targets) const {
  return check_targets(std::vector<std::optional<double>>(targets.begin(), targets.end()));
}

Result<std::vector<std::optional<double>>> ArmKinematics::device_targets(const std::vector<double>& full,
                                                                          const std::vector<bool>& sent) const {
  if (!device_) return Error{ErrorKind::unsupported, "the arm's device is not known: no device values"};
  const std::vector<double> device = model_.to_device(*device_, full);
  const DeviceRange range = device_range(*device_);
  std::vector<std::optional<double>> out(device.size());
  for (std::size_t i = 0; i < device.size(); ++i) {
    if (!sent[i]) continue;
    if (device[i] < range.min - 0.5 || device[i] > range.max + 0.5)
      return refuse(fmt::format("joint {}: {} maps to device position {:.0f}, outside what {} carries ({}..{}); "
                                "check the arm file's mapping",
                                model_.joints[i].name, format_joint_value(model_, int(i), full[i]), device[i],
                                to_string(*device_), range.min, range.max));
    out[i] = device[i];
  }
  return out;
}

}  // namespace armctl::arm

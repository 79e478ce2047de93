#include "arm/arm.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "arm/plan_moves.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"

namespace armctl::arm {

namespace {

Error refuse(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

}  // namespace

Arm::Arm(ArmModel model, std::unique_ptr<ArmDevice> device) : device_(std::move(device)) {
  if (!model.supports(device_->protocol()))
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("arm '{}' has no {} mapping for its joints, so {} cannot drive it", model.name,
                                  to_string(device_->protocol()), device_->description()));
  models_.push_back(std::make_shared<const ArmKinematics>(std::move(model), device_->protocol()));
  current_ = models_.back().get();
  kinematics_ = models_.back();
}

Status Arm::use_model(ArmModel model) {
  const ArmModel& now = this->model();
  const Protocol protocol = device_->protocol();
  if (!model.supports(protocol))
    return refuse(fmt::format("arm file {}: no {} mapping for its joints", model.file.string(), to_string(protocol)));
  if (model.joints.size() != now.joints.size())
    return refuse(fmt::format("arm file {}: {} joints where the arm has {} (open the arm again to drive another arm)",
                              model.file.string(), model.joints.size(), now.joints.size()));
  for (std::size_t i = 0; i < model.joints.size(); ++i) {
    const JointModel& a = now.joints[i];
    const JointModel& b = model.joints[i];
    if (a.name != b.name || a.map(protocol)->id != b.map(protocol)->id)
      return refuse(fmt::format("arm file {}: joint {} is {} (ID {}) where the arm has {} (ID {}): open the arm again "
                                "to drive other joints",
                                model.file.string(), i + 1, b.name, b.map(protocol)->id, a.name, a.map(protocol)->id));
  }
  auto fresh = std::make_shared<const ArmKinematics>(std::move(model), protocol);
  std::lock_guard edit(scene_edit_mutex_);
  // The scene (with its fence and reduced mode switches) checked against the new model.
  std::shared_ptr<const ArmKinematics> with_scene = fresh;
  if (fresh->collisions()) {
    auto with = fresh->with_scene(scene());
    if (!with) return with.error();
    with_scene = std::move(with).value();
  }
  std::lock_guard lock(kinematics_mutex_);
  models_.push_back(fresh);
  current_.store(fresh.get(), std::memory_order_release);
  kinematics_ = std::move(with_scene);
  last_targets_.clear();  // in the old model's values: nothing left to wait for
  return Ok{};
}

Status Arm::set_scene(scene::Scene scene) {
  auto with = current()->with_scene(std::move(scene));
  if (!with) return with.error();
  std::lock_guard lock(kinematics_mutex_);
  kinematics_ = std::move(with).value();
  return Ok{};
}

Status Arm::edit_scene(const std::function<Result<scene::Scene>(const scene::Scene&)>& edit) {
  std::lock_guard lock(scene_edit_mutex_);
  auto edited = edit(scene());
  if (!edited) return edited.error();
  return set_scene(std::move(edited).value());
}

Status Arm::set_fence(bool on) {
  return edit_scene([&](const scene::Scene& s) { return scene::with_fence(s, on); });
}

Status Arm::set_reduced_mode(bool on) {
  return edit_scene([&](const scene::Scene& s) { return scene::with_reduced_mode(s, on); });
}

scene::Scene Arm::scene() const {
  auto k = kinematics();
  return k->collisions() ? k->collisions()->scene() : scene::Scene{};
}

Result<JointState> Arm::read() {
  auto raw = device_->read_positions();
  if (!raw) return raw.error();
  JointState s;
  s.time = device_->clock().now();
  s.device = *raw;
  s.positions = model().from_device(device_->protocol(), s.device);
  return s;
}

Result<motion::Pose> Arm::pose() {
  auto s = read();
  if (!s) return s.error();
  return current()->pose_at(s->positions);
}

Status Arm::move_joints(const std::vector<std::optional<double>>& targets, const MoveOptions& options) {
  if (auto ok = current()->check_targets(targets); !ok) return ok;
  PtpMove move;
  move.target = targets;
  return move_board(std::move(move), options);
}

Status Arm::move_board(PtpMove move, const MoveOptions& options) {
  if (!options.duration)
    if (auto ok = check_fraction_in(options.speed, "speed (of the joints' velocity limits)", motion::kMinSpeedFraction,
                                    motion::kMaxSpeedFraction);
        !ok)
      return ok;
  if (options.duration && options.duration->count() < 0) return refuse("a move's duration cannot be negative");
  auto now = read();
  if (!now) return now.error();
  // A board move planned by the one planner (arm/plan_moves.hpp): the same checks and the
  // same duration rule as every app's.
  move.speed = options.speed;
  if (options.duration) move.duration = std::chrono::duration<double>(*options.duration).count();
  move.duration_words = options.duration_words;
  PlanOptions board;
  board.ptp = PtpRun::board;
  auto plan = plan_moves(*kinematics(), now->positions, std::vector<Move>{{move}}, board);
  if (!plan) return plan.error();
  if (const std::string note = plan->notes(); !note.empty() && options.on_note) options.on_note(note);
  const PlannedPiece& piece = plan->pieces.front();
  return send(piece.targets, std::chrono::duration_cast<Duration>(std::chrono::duration<double>(piece.seconds)));
}

Status Arm::send(const std::vector<std::optional<double>>& targets, Duration duration) {
  if (auto ok = current()->check_targets(targets); !ok) return ok;
  if (duration.count() < 0) return refuse("a move's duration cannot be negative");
  // A coupled joint's device value depends on its partner: the plan gives both.
  for (const Coupling& c : model().couplings)
    if (targets[std::size_t(c.first)].has_value() != targets[std::size_t(c.second)].has_value())
      return refuse(fmt::format("joints {} and {} are coupled: a move gives both or neither",
                                model().joints[std::size_t(c.first)].name, model().joints[std::size_t(c.second)].name));
  std::vector<double> full(targets.size(), 0.0);
  std::vector<bool> carried(targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    full[i] = targets[i].value_or(0.0);
    carried[i] = targets[i].has_value();
  }
  auto device_targets = current()->device_targets(full, carried);
  if (!device_targets) return device_targets.error();
  if (auto sent = device_->move(*device_targets, duration); !sent) return sent;
  last_targets_ = targets;
  move_sent_ = device_->clock().now();
  move_duration_ = duration;
  return Ok{};
}

void Arm::expect_at(const std::vector<double>& positions) {
  last_targets_.assign(positions.begin(), positions.end());
  move_sent_ = device_->clock().now();  // the executor's last point was due when its motion ended
  move_duration_ = Duration{0};
}

StallWatch Arm::stall_watch(Duration time) const {
  std::vector<StallThresholds> joints;
  for (std::size_t i = 0; i < model().joints.size(); ++i) {
    const JointModel& j = model().joints[i];
    if (model().gripper && model().gripper->joint == int(i)) {
      joints.push_back({});  // a gripper stops on a part by design
      continue;
    }
    const auto& map = j.map(device_->protocol());
    const double unit = map ? 1.0 / std::abs(map->device_per_unit()) : 0.0;
    const bool angle = j.dimension == Dimension::angle;
    joints.push_back({std::max(angle ? kStallDrivenAngle : kStallDrivenLength, 2 * unit),
                      std::max(angle ? kStallMovesAngle : kStallMovesLength, 1.5 * unit)});
  }
  return StallWatch(std::move(joints), time);
}

Error Arm::stalled(JointStall stall, const std::string& what) {
  (void)stop();  // every joint held where it stands (best effort: the stall is the news)
  const Status released = device_->release(stall.joint);
  const JointModel& j = model().joints[std::size_t(stall.joint)];
  stall.name = j.name;
  return Error{ErrorKind::device,
               fmt::format("{}joint {} stalled: it stood at {} for {:.1f} s while driven to {} (something the scene does "
                           "not know is in the way?); the arm was stopped and {}",
                           what.empty() ? "" : what + ": ", j.name, format_quantity(j.dimension, stall.position),
                           stall.seconds, format_quantity(j.dimension, stall.driven_to),
                           released ? "the joint's torque released" : "releasing its torque failed: " + released.error().message),
               stall};
}

Status Arm::move_to(const CartesianGoal& goal, const MoveOptions& options) {
  PtpMove move;
  move.target = goal;
  return move_board(std::move(move), options);
}

Status Arm::gripper(double closed_fraction, const MoveOptions& options) {
  if (!model().gripper) return Error{ErrorKind::unsupported, fmt::format("arm '{}' has no gripper", model().name)};
  if (!std::isfinite(closed_fraction) || closed_fraction < 0 || closed_fraction > 1)
    return refuse(fmt::format("gripper: {} is outside 0..1 (0 = open, 1 = closed)", closed_fraction));
  std::vector<std::optional<double>> targets(model().joints.size());
  targets[std::size_t(model().gripper->joint)] = model().gripper->at(closed_fraction);
  return move_joints(targets, options);
}

Result<JointState> Arm::wait(const WaitOptions& options) {
  const TimePoint deadline = device_->clock().now() + options.timeout;
  std::optional<JointState> previous;
  StallWatch stall = stall_watch(options.stall_time);
  std::vector<std::optional<double>> driven_to(last_targets_.size());
  for (;;) {
    auto s = read();
    if (!s) return s.error();
    if (options.on_read) options.on_read(*s);
    // Driven to its target once the move's time is up. Not before: where the board has a
    // joint meanwhile is the board's (the arm controller starts a joint late so that every
    // joint arrives together; an xArm servo moves at once).
    const bool due = s->time >= move_sent_ + move_duration_;
    for (std::size_t i = 0; i < last_targets_.size(); ++i) driven_to[i] = due ? last_targets_[i] : std::nullopt;
    if (auto st = stall.read(s->time, s->positions, driven_to)) return stalled(std::move(*st));
    std::string late;
    bool resting = previous.has_value();
    for (std::size_t i = 0; i < last_targets_.size(); ++i) {
      if (!last_targets_[i]) continue;
      const JointModel& j = model().joints[i];
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

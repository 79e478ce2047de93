#include "arm/servo_commands.hpp"

#include <cmath>

#include <fmt/format.h>

namespace armctl::arm {

const char* to_string(ServoFrame frame) { return frame == ServoFrame::base ? "base" : "tool"; }

ServoInput::ServoInput(const ArmModel& model) : model_(model) {}

namespace {

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

Error bad(std::string message) { return Error{ErrorKind::invalid_argument, std::move(message)}; }

}  // namespace

Status ServoInput::check(const ServoCommand& c) const {
  const std::size_t n = std::size_t(model_.joint_count());
  if (c.gripper && !(*c.gripper >= 0 && *c.gripper <= 1))
    return bad(fmt::format("servo gripper {}: a closed fraction from 0 (open) to 1 (closed)", *c.gripper));
  if (c.gripper && !model_.gripper) return bad(fmt::format("servo gripper: arm '{}' has no gripper", model_.name));
  if (const auto* t = std::get_if<ToolTwist>(&c.motion)) {
    if (!finite(t->linear) || !finite(t->angular))
      return bad("servo twist: every linear (mm/s) and angular (deg/s) component must be a finite number");
  } else if (const auto* v = std::get_if<JointVelocities>(&c.motion)) {
    if (v->values.size() != n)
      return bad(fmt::format("servo joint velocities: {} values, arm '{}' has {} joints", v->values.size(),
                             model_.name, n));
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(v->values[i]))
        return bad(fmt::format("servo joint velocities: joint {} is {}, a finite number is needed",
                               model_.joints[i].name, v->values[i]));
  } else if (const auto* j = std::get_if<JointTargets>(&c.motion)) {
    if (j->values.size() != n)
      return bad(fmt::format("servo joint targets: {} values, arm '{}' has {} joints", j->values.size(), model_.name,
                             n));
    for (std::size_t i = 0; i < n; ++i)
      if (j->values[i] && !std::isfinite(*j->values[i]))
        return bad(fmt::format("servo joint targets: joint {} is {}, a finite number is needed",
                               model_.joints[i].name, *j->values[i]));
  } else if (const auto* p = std::get_if<PoseTarget>(&c.motion)) {
    const auto finite_or_empty = [](const std::optional<double>& x) { return !x || std::isfinite(*x); };
    if (!finite(p->goal.position) || !finite_or_empty(p->goal.roll) || !finite_or_empty(p->goal.pitch) ||
        !finite_or_empty(p->goal.yaw))
      return bad("servo pose target: position and orientation must be finite numbers");
  }
  return Ok{};
}

Status ServoInput::send(ServoCommand command) {
  if (auto ok = check(command); !ok) return ok;
  std::lock_guard lock(mutex_);
  command_ = std::move(command);
  ++sequence_;
  return Ok{};
}

void ServoInput::finish() {
  std::lock_guard lock(mutex_);
  finish_ = true;
}

bool ServoInput::finishing() const {
  std::lock_guard lock(mutex_);
  return finish_;
}

ServoInput::Newest ServoInput::take(std::uint64_t seen) const {
  std::lock_guard lock(mutex_);
  if (sequence_ == seen) return {std::nullopt, sequence_, finish_};
  return {command_, sequence_, finish_};
}

}  // namespace armctl::arm

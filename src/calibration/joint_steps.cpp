#include "calibration/joint_steps.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

namespace armctl::calibration {

namespace {

Error refuse(std::string m) { return Error{ErrorKind::invalid_argument, std::move(m)}; }

Status check_joint(const arm::ArmModel& model, int joint) {
  if (joint < 0 || joint >= model.joint_count())
    return refuse(fmt::format("no joint {} (arm '{}' has joints 0..{})", joint, model.name, model.joint_count() - 1));
  return Ok{};
}

}  // namespace

double limit_margin(const arm::JointModel& joint) {
  return joint.dimension == Dimension::angle ? kLimitMarginAngle : kLimitMarginLength;
}

double mark_of(const arm::JointModel& joint) {
  const double inside = limit_margin(joint) * 2;
  return std::clamp(0.0, joint.urdf_lower + inside, joint.urdf_upper - inside);
}

std::optional<JointChange> direction_from_answer(const arm::ArmModel& model, int joint, bool went_as_shown) {
  if (went_as_shown || joint < 0 || joint >= model.joint_count()) return std::nullopt;
  JointChange c;
  c.joint = model.joints[std::size_t(joint)].name;
  c.flip = true;
  return c;
}

Result<ZeroStep> zero_at_mark(const arm::ArmModel& model, arm::Protocol protocol, const JointAtMark& at) {
  if (Status s = check_joint(model, at.joint); !s) return s.error();
  const arm::JointModel& j = model.joints[std::size_t(at.joint)];
  const arm::DeviceMap* map = j.map(protocol);
  if (!map) return refuse(fmt::format("joint {} has no {} map", j.name, to_string(protocol)));
  if (!std::isfinite(at.reading) || !std::isfinite(at.device) || !std::isfinite(at.mark))
    return refuse(fmt::format("joint {}: the reading at its mark is not a number", j.name));
  ZeroStep step;
  auto file_zero = [&](double reading_now, std::string why) {
    step.kind = ZeroStep::Kind::file_zero;
    step.change = JointChange{j.name, false, at.mark - reading_now, std::nullopt};
    step.why = std::move(why);
    return step;
  };
  if (at.servo_offsets) {
    if (at.servo_offset < -125 || at.servo_offset > 125)
      return refuse(fmt::format("servo {} ({}): offset {} read back is outside -125..125", map->id, j.name, at.servo_offset));
    // Commanded `want` (the device position of the mark) must put the shaft at the mark:
    // the shaft stands at commanded + offset (the reading, in the commanded frame, plus the
    // offset held now), and it stands at the mark now.
    const double want = map->to_device(at.mark);
    const double shaft = at.device + at.servo_offset;
    const long units = std::lround(shaft - want);
    if (units >= -125 && units <= 125) {
      step.kind = ZeroStep::Kind::servo_offset;
      step.servo_offset = ServoOffset{j.name, map->id, int(units)};
      step.why = fmt::format("servo {}'s shaft stands at {:.0f} at the mark of {}, {:.0f} wanted: its offset becomes {} "
                             "(within -125..125)",
                             map->id, shaft, j.name, want, units);
      return step;
    }
    return file_zero(at.reading, fmt::format("servo {} would need offset {}, beyond its -125..125 (30 deg): the arm "
                                             "file's zero of {} moves instead",
                                             map->id, units, j.name));
  }
  if (protocol == arm::Protocol::joint_bus) {
    // After `home` the joint's count is 0 (its partner's too, for a coupled pair homed together).
    std::vector<double> device(model.joints.size(), 0.0);
    const double after_home = model.from_device(protocol, device)[std::size_t(at.joint)];
    step.kind = ZeroStep::Kind::home;
    if (std::abs(after_home - at.mark) > 1e-12)
      step.change = JointChange{j.name, false, at.mark - after_home, std::nullopt};
    step.why = fmt::format("joint {}: `home` makes its count 0 where it stands{}", j.name,
                           step.change ? ", and the arm file reads count 0 as the mark" : "");
    return step;
  }
  return file_zero(at.reading, fmt::format("joint {}: the arm file's zero moves to where it stands", j.name));
}

Result<PositionRange> limits_from_ends(const arm::ArmModel& model, int joint, double end_a, double end_b,
                                       std::optional<double> margin) {
  if (Status s = check_joint(model, joint); !s) return s.error();
  const arm::JointModel& j = model.joints[std::size_t(joint)];
  const double m = margin.value_or(limit_margin(j));
  if (!std::isfinite(end_a) || !std::isfinite(end_b) || !std::isfinite(m) || m < 0)
    return refuse(fmt::format("joint {}: the ends and the margin must be finite numbers, the margin >= 0", j.name));
  PositionRange r{std::min(end_a, end_b) + m, std::max(end_a, end_b) - m};
  if (!(r.lower < r.upper))
    return refuse(fmt::format("joint {}: its ends {} and {} leave no travel inside a margin of {} at each end", j.name,
                              format_quantity(j.dimension, end_a), format_quantity(j.dimension, end_b),
                              format_quantity(j.dimension, m)));
  if (!(r.lower <= 0 && 0 <= r.upper))
    return refuse(fmt::format("joint {}: limits {}..{} (the ends less the margin) would exclude its zero; set the "
                              "zero first, or move the joint to its true ends",
                              j.name, format_quantity(j.dimension, r.lower), format_quantity(j.dimension, r.upper)));
  return r;
}

Result<GripperPositions> gripper_from_readings(const arm::ArmModel& model, double open, double closed) {
  if (!model.gripper) return refuse(fmt::format("arm '{}' has no gripper", model.name));
  const arm::JointModel& j = model.joints[std::size_t(model.gripper->joint)];
  if (!std::isfinite(open) || !std::isfinite(closed))
    return refuse(fmt::format("gripper {}: the readings must be numbers", j.name));
  if (std::abs(open - closed) < 2 * limit_margin(j))
    return refuse(fmt::format("gripper {}: open {} and closed {} are too close to tell apart (at least {} apart)",
                              j.name, format_quantity(j.dimension, open), format_quantity(j.dimension, closed),
                              format_quantity(j.dimension, 2 * limit_margin(j))));
  return GripperPositions{open, closed};
}

}  // namespace armctl::calibration

#include "calibration/calibration_changes.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/core.h>

#include "arm/arm_calibration.hpp"
#include "core/printable.hpp"

namespace armctl::calibration {

namespace {

Error refuse(std::string m) { return Error{ErrorKind::invalid_argument, std::move(m)}; }

// A limit this close to a bound is on it (rounding of values written with 6 decimals).
constexpr double kSlack = 1e-9;

const arm::Coupling* coupling_of(const arm::ArmModel& model, int joint) {
  for (const arm::Coupling& c : model.couplings)
    if (c.first == joint || c.second == joint) return &c;
  return nullptr;
}

std::string q(const arm::JointModel& j, double v) { return format_quantity(j.dimension, v); }

}  // namespace

CalibrationChanges from_zero_changes(const arm::ArmModel& model, const std::vector<arm::ZeroChange>& zeros) {
  // calibrate_zero's shift is the actuator's value where it stands; the joint's is the
  // coupling's inverse of its pair's (the joint's own for a joint alone).
  std::vector<double> actuator(model.joints.size(), 0.0);
  for (const arm::ZeroChange& z : zeros) actuator[std::size_t(z.joint)] = z.shift;
  std::vector<double> joint = actuator;
  for (const arm::Coupling& k : model.couplings) {
    const double a = actuator[std::size_t(k.first)], b = actuator[std::size_t(k.second)];
    const double det = k.matrix[0][0] * k.matrix[1][1] - k.matrix[0][1] * k.matrix[1][0];
    joint[std::size_t(k.first)] = (k.matrix[1][1] * a - k.matrix[0][1] * b) / det;
    joint[std::size_t(k.second)] = (-k.matrix[1][0] * a + k.matrix[0][0] * b) / det;
  }
  CalibrationChanges c;
  for (const arm::ZeroChange& z : zeros)
    c.joints.push_back(JointChange{model.joints[std::size_t(z.joint)].name, false, -joint[std::size_t(z.joint)],
                                   PositionRange{z.limits.lower, z.limits.upper}});
  return c;
}

std::string quantity_text(Dimension dimension, double si) {
  return fmt::format("{:.6f}{}", to_display(dimension, si), display_unit(dimension));
}

Result<CheckedChanges> check_changes(const arm::ArmModel& model, const CalibrationChanges& changes) {
  CheckedChanges out;
  out.changes = changes;
  // Each joint's change by index; joints not named keep flip false, shift 0.
  std::vector<const JointChange*> by_joint(model.joints.size(), nullptr);
  for (const JointChange& c : changes.joints) {
    auto found = model.find_joint(c.joint);
    if (!found) return refuse(fmt::format("no joint named '{}' on arm '{}'", printable(c.joint), model.name));
    if (by_joint[std::size_t(*found)]) return refuse(fmt::format("joint {} is changed twice", c.joint));
    if (!std::isfinite(c.zero_shift)) return refuse(fmt::format("joint {}: the zero shift is not a number", c.joint));
    by_joint[std::size_t(*found)] = &c;
  }
  // A coupled pair's actuators each carry both joints: a shift of the joints is a shift of
  // the actuators by the coupling matrix, and a flip must be of both (the matrix then
  // commutes with it).
  std::vector<double> actuator_shift(model.joints.size(), 0.0);
  for (int i = 0; i < model.joint_count(); ++i)
    if (by_joint[std::size_t(i)] && !coupling_of(model, i)) actuator_shift[std::size_t(i)] = by_joint[std::size_t(i)]->zero_shift;
  for (const arm::Coupling& k : model.couplings) {
    const JointChange* a = by_joint[std::size_t(k.first)];
    const JointChange* b = by_joint[std::size_t(k.second)];
    if (!a && !b) continue;
    const bool fa = a && a->flip, fb = b && b->flip;
    if (fa != fb)
      return refuse(fmt::format("joints {} and {} are coupled: a direction flip of one alone mixes their actuators; "
                                "flip both, or neither",
                                model.joints[std::size_t(k.first)].name, model.joints[std::size_t(k.second)].name));
    const double sa = a ? a->zero_shift : 0, sb = b ? b->zero_shift : 0;
    actuator_shift[std::size_t(k.first)] = k.matrix[0][0] * sa + k.matrix[0][1] * sb;
    actuator_shift[std::size_t(k.second)] = k.matrix[1][0] * sa + k.matrix[1][1] * sb;
  }
  // The partner of a changed coupled joint changes with it (its actuator shifts), as itself
  // unchanged: no flip, no shift, its limits as they were.
  std::vector<JointChange> partners;
  partners.reserve(model.couplings.size() * 2);
  for (const arm::Coupling& k : model.couplings)
    for (auto [a, b] : {std::pair{k.first, k.second}, std::pair{k.second, k.first}})
      if (by_joint[std::size_t(a)] && !by_joint[std::size_t(b)])
        partners.push_back(JointChange{model.joints[std::size_t(b)].name, by_joint[std::size_t(a)]->flip, 0, std::nullopt});
  std::vector<const JointChange*> resolved = by_joint;
  for (const JointChange& c : partners) resolved[std::size_t(*model.find_joint(c.joint))] = &c;
  for (int i = 0; i < model.joint_count(); ++i) {
    const JointChange* c = resolved[std::size_t(i)];
    if (!c) continue;
    const arm::JointModel& j = model.joints[std::size_t(i)];
    const double sign = c->flip ? -1.0 : 1.0;
    CheckedJoint cj;
    cj.index = i;
    cj.devices = j.devices;
    for (auto& [name, map] : cj.devices) {
      map.actuator_a = sign * map.actuator_a + actuator_shift[std::size_t(i)];
      map.actuator_b = sign * map.actuator_b + actuator_shift[std::size_t(i)];
    }
    cj.limits = j.limits;
    if (c->limits) {
      if (!std::isfinite(c->limits->lower) || !std::isfinite(c->limits->upper) || !(c->limits->lower < c->limits->upper))
        return refuse(fmt::format("joint {}: limits {}..{} must be finite with lower below upper", j.name,
                                  q(j, c->limits->lower), q(j, c->limits->upper)));
      cj.limits.lower = c->limits->lower;
      cj.limits.upper = c->limits->upper;
    } else {
      // The old travel in the new readings, within what the URDF allows.
      const double a = sign * j.limits.lower + c->zero_shift, b = sign * j.limits.upper + c->zero_shift;
      cj.limits.lower = std::max(std::min(a, b), j.urdf_lower);
      cj.limits.upper = std::min(std::max(a, b), j.urdf_upper);
    }
    const arm::JointLimits& l = cj.limits;
    if (!(l.lower <= kSlack && -kSlack <= l.upper))
      return refuse(fmt::format("joint {}: limits {}..{} exclude its zero; a joint's zero must lie within its travel",
                                j.name, q(j, l.lower), q(j, l.upper)));
    if (l.lower < j.urdf_lower - kSlack || l.upper > j.urdf_upper + kSlack)
      return refuse(fmt::format("joint {}: limits {}..{} reach beyond the URDF's {}..{}", j.name, q(j, l.lower),
                                q(j, l.upper), q(j, j.urdf_lower), q(j, j.urdf_upper)));
    if (!coupling_of(model, i)) {
      for (const auto& [name, map] : cj.devices) {
        const arm::DeviceRange range = arm::device_range(*arm::find_protocol(name));
        for (double v : {l.lower, l.upper}) {
          const double d = map.to_device(v);
          if (d < range.min - kSlack || d > range.max + kSlack)
            return refuse(fmt::format("joint {}: its limit {} is device position {:.1f} on {}, outside the device's "
                                      "range {}..{}",
                                      j.name, q(j, v), d, name, range.min, range.max));
        }
      }
    }
    out.joints.push_back(std::move(cj));
  }
  // A coupled pair's limits: every corner of their box inside each actuator's range.
  if (!model.couplings.empty() && !out.joints.empty()) {
    arm::ArmModel changed = model;
    for (const CheckedJoint& cj : out.joints) {
      changed.joints[std::size_t(cj.index)].devices = cj.devices;
      changed.joints[std::size_t(cj.index)].limits = cj.limits;
    }
    for (const arm::Coupling& k : model.couplings) {
      if (!by_joint[std::size_t(k.first)] && !by_joint[std::size_t(k.second)]) continue;
      for (arm::Protocol p : arm::protocols()) {
        if (!changed.supports(p)) continue;
        const arm::DeviceRange range = arm::device_range(p);
        if (auto over = arm::coupled_overrun(changed, p, k, kSlack))
          return refuse(fmt::format("joints {} and {}: the ends of their limits need device position {:.0f} on {}, "
                                    "outside {}..{}",
                                    model.joints[std::size_t(k.first)].name, model.joints[std::size_t(k.second)].name,
                                    over->device, to_string(p), range.min, range.max));
      }
    }
  }
  if (changes.gripper && !model.gripper) return refuse(fmt::format("arm '{}' has no gripper", model.name));
  if (model.gripper && (changes.gripper || by_joint[std::size_t(model.gripper->joint)])) {
    const int g = model.gripper->joint;
    const arm::JointModel& j = model.joints[std::size_t(g)];
    arm::JointLimits l = j.limits;
    for (const CheckedJoint& cj : out.joints)
      if (cj.index == g) l = cj.limits;
    GripperPositions gp{model.gripper->open, model.gripper->closed};
    if (changes.gripper) {
      gp = *changes.gripper;
    } else {
      const JointChange& c = *by_joint[std::size_t(g)];
      const double sign = c.flip ? -1.0 : 1.0;
      gp = GripperPositions{sign * gp.open + c.zero_shift, sign * gp.closed + c.zero_shift};
    }
    out.gripper = gp;
    if (!std::isfinite(gp.open) || !std::isfinite(gp.closed) || gp.open == gp.closed)
      return refuse(fmt::format("gripper {}: open and closed must be two different positions", j.name));
    for (double v : {gp.open, gp.closed})
      if (!l.contains(v, kSlack))
        return refuse(fmt::format("gripper {}: position {} lies outside its limits {}..{}", j.name, q(j, v),
                                  q(j, l.lower), q(j, l.upper)));
  }
  // Link lengths: the model's, with these replacing theirs.
  out.link_lengths = model.link_lengths;
  for (const motion::OriginLength& l : changes.link_lengths) {
    if (!std::isfinite(l.length) || !(l.length > 0) || l.length > 100)
      return refuse(fmt::format("link length of {}: {} is not a length above 0 and at most 100 m", printable(l.joint),
                                l.length));
    const bool on_chain =
        model.chain && (std::any_of(model.chain->joints.begin(), model.chain->joints.end(),
                                    [&](const motion::ChainJoint& c) { return c.name == l.joint; }) ||
                        std::any_of(model.chain->fixed.begin(), model.chain->fixed.end(),
                                    [&](const motion::FixedChainJoint& c) { return c.name == l.joint; }));
    if (!on_chain)
      return refuse(fmt::format("link length of {}: not a joint of arm '{}''s chain", printable(l.joint), model.name));
    auto it = std::find_if(out.link_lengths.begin(), out.link_lengths.end(),
                           [&](const motion::OriginLength& o) { return o.joint == l.joint; });
    if (it != out.link_lengths.end()) it->length = l.length;
    else out.link_lengths.push_back(l);
  }
  std::set<std::string> offset_joints;
  for (const ServoOffset& o : changes.servo_offsets) {
    auto found = model.find_joint(o.joint);
    if (!found) return refuse(fmt::format("servo offset: no joint named '{}'", printable(o.joint)));
    const arm::JointModel& j = model.joints[std::size_t(*found)];
    const arm::DeviceMap* map = j.map(arm::Protocol::robot_commands);
    if (!map) return refuse(fmt::format("joint {} has no Robot Commands servo to hold an offset", j.name));
    if (o.servo != map->id)
      return refuse(fmt::format("joint {} is servo {}, not {}", j.name, map->id, o.servo));
    if (o.units < -125 || o.units > 125)
      return refuse(fmt::format("servo {} ({}): offset {} is outside the servo's -125..125", o.servo, j.name, o.units));
    if (!offset_joints.insert(j.name).second) return refuse(fmt::format("joint {}: two servo offsets", j.name));
    if (by_joint[std::size_t(*found)] && by_joint[std::size_t(*found)]->zero_shift != 0)
      return refuse(fmt::format("joint {}: its zero is set both by the servo's offset and by the arm file; choose one",
                                j.name));
  }
  return out;
}

Result<nlohmann::json> apply_changes(nlohmann::json doc, const arm::ArmModel& model, const CheckedChanges& checked) {
  using nlohmann::json;
  const std::string file = model.file.empty() ? model.name : model.file.string();
  if (!doc.is_object() || !doc.contains("joints") || !doc["joints"].is_array())
    return Error{ErrorKind::invalid_config, fmt::format("{}: no joints array", printable(file))};
  for (const CheckedJoint& cj : checked.joints) {
    const arm::JointModel& j = model.joints[std::size_t(cj.index)];
    json* entry = nullptr;
    for (auto& e : doc["joints"])
      if (e.is_object() && e.value("name", "") == j.name) entry = &e;
    if (!entry) return Error{ErrorKind::invalid_config, fmt::format("{}: joint {} not found", printable(file), j.name)};
    for (const auto& [name, map] : cj.devices) {
      if (!entry->contains(name)) continue;
      (*entry)[name]["joint"] = json::array({quantity_text(j.dimension, map.actuator_a), quantity_text(j.dimension, map.actuator_b)});
    }
    (*entry)["limits"]["position"] =
        json::array({quantity_text(j.dimension, cj.limits.lower), quantity_text(j.dimension, cj.limits.upper)});
  }
  if (checked.gripper && model.gripper) {
    const arm::JointModel& j = model.joints[std::size_t(model.gripper->joint)];
    doc["gripper"]["open"] = quantity_text(j.dimension, checked.gripper->open);
    doc["gripper"]["closed"] = quantity_text(j.dimension, checked.gripper->closed);
  }
  if (!checked.link_lengths.empty()) {
    json lengths = json::object();
    lengths["comment"] =
        "Calibrated lengths of URDF joint origins (the offset's direction kept), applied to the URDF on load: "
        "docs/calibration.md.";
    for (const motion::OriginLength& l : checked.link_lengths) lengths[l.joint] = quantity_text(Dimension::length, l.length);
    doc["link_lengths"] = lengths;
  }
  return doc;
}

}  // namespace armctl::calibration

#include "web/state_json.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "core/quantity.hpp"
#include "web/display_value.hpp"
#include "web/error_detail.hpp"

namespace armctl::web {

namespace {

double deg(double rad) { return display_value(Dimension::angle, rad); }
double mm(double m) { return display_value(Dimension::length, m); }

// A number JSON can carry (NaN and infinities become null).
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

DeviceInfo describe_device(session::ArmSession& session, const std::string& uri) {
  DeviceInfo d;
  d.device = uri;
  d.description = session.arm->device().description();
  d.protocol = session.arm->device().protocol();
  d.groups_supported = session.arm->device().action_groups() != nullptr;
  d.reconnects = uri.empty() || session.reconnects;
  return d;
}

json model_json(const arm::ArmModel& model, const DeviceInfo& device) {
  json joints = json::array();
  const auto range = arm::device_range(device.protocol);
  for (const auto& j : model.joints) {
    json joint{{"name", j.name},
               {"kind", j.dimension == Dimension::angle ? "revolute" : "prismatic"},
               {"unit", display_unit(j.dimension)},
               {"min", display_value(j.dimension, j.limits.lower)},
               {"max", display_value(j.dimension, j.limits.upper)},
               {"max_velocity", display_value(j.dimension, j.limits.velocity)},  // per second
               {"gripper", j.role == arm::JointRole::gripper},
               {"raw_unit", arm::protocol_info(device.protocol).raw_unit}};
    if (const auto& map = j.map(device.protocol)) {
      const double a = std::clamp(map->to_device(j.limits.lower), range.min, range.max);
      const double b = std::clamp(map->to_device(j.limits.upper), range.min, range.max);
      joint["raw_min"] = std::round(std::min(a, b));
      joint["raw_max"] = std::round(std::max(a, b));
    } else {
      joint["raw_min"] = nullptr;
      joint["raw_max"] = nullptr;
    }
    joints.push_back(std::move(joint));
  }
  const motion::Rpy rpy = motion::to_rpy(model.tool.orientation);
  const std::string tool_frame =
      fmt::format("x {:.1f} y {:.1f} z {:.1f} mm, roll {:.1f} pitch {:.1f} yaw {:.1f} deg in the URDF's tool link",
                  mm(model.tool.position.x()), mm(model.tool.position.y()), mm(model.tool.position.z()), deg(rpy.roll),
                  deg(rpy.pitch), deg(rpy.yaw));
  return {{"arm", model.name},
          {"description", device.description},
          {"device", device.device.empty() ? "embedded simulator" : device.device},
          {"protocol", arm::to_string(device.protocol)},
          {"joints", std::move(joints)},
          {"tool_frame", tool_frame},
          // The same as numbers, as a scene object is placed (docs/scene.md): where the
          // dashboard hangs the parts the tool holds.
          {"tool_link", model.tool_link},
          {"tool_offset", {{"at", {mm(model.tool.position.x()), mm(model.tool.position.y()), mm(model.tool.position.z())}},
                           {"rpy", {deg(rpy.roll), deg(rpy.pitch), deg(rpy.yaw)}}}},
          {"has_gripper", model.gripper.has_value()},
          {"groups_supported", device.groups_supported}};
}

json tool_json(const arm::ArmKinematics& arm, const motion::Pose& pose, const std::vector<double>& positions) {
  const motion::Rpy rpy = arm.tool_rpy(pose, arm.chain_of(positions));
  return {{"x", mm(pose.position.x())}, {"y", mm(pose.position.y())}, {"z", mm(pose.position.z())},
          {"roll", deg(rpy.roll)},      {"pitch", deg(rpy.pitch)},    {"yaw", deg(rpy.yaw)}};
}

json state_json(const arm::ArmKinematics& arm, const DeviceInfo& device, const session::ArmSnapshot& s,
                const ControlView& control, const std::optional<ProgramView>& program) {
  const arm::ArmModel& model = arm.model();
  json joints = json::array();
  for (std::size_t i = 0; i < model.joints.size(); ++i) {
    const auto& j = model.joints[i];
    json joint{{"name", j.name}};
    joint["position"] = i < s.positions.size() ? number(display_value(j.dimension, s.positions[i])) : json(nullptr);
    joint["raw"] = i < s.device.size() ? number(s.device[i]) : json(nullptr);
    joint["velocity"] = i < s.velocities.size() ? number(display_value(j.dimension, s.velocities[i])) : json(nullptr);
    joints.push_back(std::move(joint));
  }
  json out{{"sequence", s.sequence},
           {"link", {{"ok", s.link_ok}, {"error", s.link_error}, {"reconnects", device.reconnects}}},
           {"joints", std::move(joints)},
           {"tool", s.pose && s.positions.size() == model.joints.size() ? tool_json(arm, *s.pose, s.positions)
                                                                        : json(nullptr)},
           {"battery_volts", s.status.battery_volts ? number(*s.status.battery_volts) : json(nullptr)},
           {"faults", s.status.faults},
           {"job", s.job},
           {"last_error", s.last_error},
           {"last_collision", s.last_collision ? collision_json(*s.last_collision, model) : json(nullptr)}};
  if (s.progress)
    out["motion"] = {{"t", s.progress->t}, {"duration", s.progress->duration}, {"paused", s.progress->paused}};
  else
    out["motion"] = nullptr;
  if (program)
    out["program"] = {{"line", program->line},
                      {"column", program->column},
                      {"left_s", program->left_s},
                      {"state", to_string(program->state)},
                      {"prints", program->prints}};
  else
    out["program"] = nullptr;
  out["control"] = {{"you", control.you}, {"holder", control.holder}, {"since", control.since}};
  // Which of the scene's limits plans are checked with now (docs/scene.md "Fence and reduced
  // mode"): the dashboard's status line shows them.
  const auto& world = arm.collisions();
  const auto* fence = world && world->scene().fence ? &*world->scene().fence : nullptr;
  const auto* reduced = world && world->scene().reduced ? &*world->scene().reduced : nullptr;
  out["limits"] = {{"fence", fence ? json(fence->on) : json(nullptr)}, {"reduced", reduced ? json(reduced->on) : json(nullptr)}};
  return out;
}

}  // namespace armctl::web

#include "web/calibration_request.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "core/quantity.hpp"
#include "web/api_error.hpp"

namespace armctl::web {

namespace {

// A joint field: its name or its 0-based index.
int joint_field(const arm::ArmModel& model, BodyReader& r, const std::string& key) {
  std::string names;
  for (const auto& j : model.joints) names += (names.empty() ? "\"" : ", \"") + j.name + "\"";
  const std::string allowed = fmt::format("a joint's name ({}) or index 0..{}", names, model.joint_count() - 1);
  const json& v = r.require(key, allowed);
  if (v.is_string())
    if (auto i = model.find_joint(v.get_ref<const std::string&>())) return *i;
  if (v.is_number_integer()) {
    const auto i = v.get<std::int64_t>();
    if (i >= 0 && i < model.joint_count()) return int(i);
  }
  bad_value(r.name(key), fmt::format("{} is not allowed; {}", shown(v), allowed));
}

// A joint's value as the API gives it (deg or mm), in SI: finite and of a size a joint can have.
double reading(const arm::ArmModel& model, int joint, BodyReader& r, const std::string& key, const char* what) {
  const Dimension d = model.joints[std::size_t(joint)].dimension;
  return from_display(d, r.number(key, -1e5, 1e5, fmt::format("{} of {} in {}", what, model.joints[std::size_t(joint)].name, display_unit(d))));
}
std::optional<double> optional_reading(const arm::ArmModel& model, int joint, BodyReader& r, const std::string& key,
                                       const char* what) {
  if (!r.has(key)) return std::nullopt;
  return reading(model, joint, r, key, what);
}

}  // namespace

CalibrationRequest parse_calibration_request(const arm::ArmModel& model, const std::string& step, const json& body) {
  if (std::find(kCalibrationSteps.begin(), kCalibrationSteps.end(), step) == kCalibrationSteps.end()) {
    std::string allowed;
    for (const auto& s : kCalibrationSteps) allowed += (allowed.empty() ? "" : ", ") + s;
    throw ApiError(400, fmt::format("calibration step '{}' is not allowed; one of {}", step, allowed));
  }
  CalibrationRequest q;
  q.step = step;
  BodyReader r(body);
  if (step == "start") {
    q.servo_offsets = r.optional_boolean("servo_offsets").value_or(true);
  } else if (step == "wiggle" || step == "nudge" || step == "read") {
    q.joint = joint_field(model, r, "joint");
  } else if (step == "which") {
    q.joint = joint_field(model, r, "joint");
    q.moved = joint_field(model, r, "moved");
  } else if (step == "direction") {
    q.joint = joint_field(model, r, "joint");
    q.went_as_shown = r.boolean("went_as_shown");
  } else if (step == "zero") {
    q.joint = joint_field(model, r, "joint");
    q.mark = optional_reading(model, q.joint, r, "mark", "the true value at its mark");
  } else if (step == "limits") {
    q.joint = joint_field(model, r, "joint");
    q.end_a = reading(model, q.joint, r, "end_a", "a reading");
    q.end_b = reading(model, q.joint, r, "end_b", "a reading");
  } else if (step == "gripper") {
    if (!model.gripper) throw ApiError(409, fmt::format("arm {} has no gripper", model.name));
    q.open = reading(model, model.gripper->joint, r, "open", "a reading");
    q.closed = reading(model, model.gripper->joint, r, "closed", "a reading");
  } else if (step == "touch") {
    q.name = r.string("name", 64);
    const json& p = r.require("position", "[x, y, z] in mm");
    if (!p.is_array() || p.size() != 3 || !std::all_of(p.begin(), p.end(), [](const json& x) { return x.is_number(); }))
      bad_value(r.name("position"), fmt::format("{} is not allowed; [x, y, z] in mm", shown(p)));
    for (int i = 0; i < 3; ++i) q.position[i] = p[std::size_t(i)].get<double>() / 1000;
    if (!q.position.allFinite() || q.position.norm() > kMaxReach)
      bad_value(r.name("position"), fmt::format("{} is not allowed; finite, within {} mm of the base", shown(p), kMaxReach * 1000));
  } else if (step == "forget") {
    if (r.has("joint")) q.joint = joint_field(model, r, "joint");
  }
  r.finish();
  return q;
}

}  // namespace armctl::web

#include "web/calibration_request.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

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

// A reading (rad or m): finite and of a size a joint can have.
double reading(BodyReader& r, const std::string& key) { return r.number(key, -100, 100, "a joint reading in rad or m"); }

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
    q.servo_offsets = r.optional_boolean("servo_offsets").value_or(false);
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
    q.mark = r.optional_number("mark", -100, 100, "the joint's true value at its mark, rad or m");
  } else if (step == "limits") {
    q.joint = joint_field(model, r, "joint");
    q.end_a = reading(r, "end_a");
    q.end_b = reading(r, "end_b");
  } else if (step == "gripper") {
    q.open = reading(r, "open");
    q.closed = reading(r, "closed");
  } else if (step == "touch") {
    q.name = r.string("name", 64);
    const json& p = r.require("position", "[x, y, z] in m");
    if (!p.is_array() || p.size() != 3 || !std::all_of(p.begin(), p.end(), [](const json& x) { return x.is_number(); }))
      bad_value(r.name("position"), fmt::format("{} is not allowed; [x, y, z] in m", shown(p)));
    for (int i = 0; i < 3; ++i) q.position[i] = p[std::size_t(i)].get<double>();
    if (!q.position.allFinite() || q.position.norm() > kMaxReach)
      bad_value(r.name("position"), fmt::format("{} is not allowed; finite, within {} m of the base", shown(p), kMaxReach));
  } else if (step == "forget") {
    if (r.has("joint")) q.joint = joint_field(model, r, "joint");
  }
  r.finish();
  return q;
}

}  // namespace armctl::web

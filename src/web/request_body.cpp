#include "web/request_body.hpp"

#include <cmath>

#include <fmt/core.h>

#include "arm/avoid_path.hpp"
#include "core/printable.hpp"
#include "core/quantity.hpp"
#include "core/strict_json.hpp"
#include "files/points_file.hpp"
#include "web/api_error.hpp"

namespace armctl::web {

namespace {

// A joint's range for people: "-90..90 deg".
std::string joint_range(const arm::JointModel& j) {
  return fmt::format("{:g}..{:g} {}", to_display(j.dimension, j.limits.lower), to_display(j.dimension, j.limits.upper),
                     display_unit(j.dimension));
}

std::string joint_names(const arm::ArmModel& model) {
  std::string names;
  for (const auto& j : model.joints) names += (names.empty() ? "" : ", ") + j.name;
  return names;
}

}  // namespace

[[noreturn]] void bad_value(const std::string& field, const std::string& why) {
  throw ApiError(400, fmt::format("{}: {}", printable(field), why));
}

std::string shown(const json& value) {
  std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return printable(text);
}

json parse_body(std::string_view text) {
  if (text.size() > kMaxBodyBytes)
    throw ApiError(413, fmt::format("the request body is {} bytes; at most {} bytes (1 MiB) are allowed", text.size(),
                                    kMaxBodyBytes));
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) return json::object();
  Result<json> body = parse_strict_json(text, kMaxBodyDepth);
  if (!body) throw ApiError(400, "the request body: " + body.error().message);
  if (!body->is_object()) throw ApiError(400, "the request body must be a JSON object ({...})");
  return std::move(body).value();
}

BodyReader::BodyReader(const json& object, std::string path) : object_(object), path_(std::move(path)) {
  if (!object_.is_object())
    bad_value(path_.empty() ? "the request body" : path_.substr(0, path_.size() - 1), "must be a JSON object");
}

const json* BodyReader::find(const std::string& key) {
  known_.insert(key);
  auto it = object_.find(key);
  return it == object_.end() || it->is_null() ? nullptr : &*it;
}

const json& BodyReader::require(const std::string& key, const std::string& allowed) {
  const json* v = find(key);
  if (v == nullptr) bad_value(name(key), fmt::format("missing; {}", allowed));
  return *v;
}

double BodyReader::number(const std::string& key, double min, double max, const std::string& allowed, bool above_min) {
  auto v = optional_number(key, min, max, allowed, above_min);
  if (!v) bad_value(name(key), fmt::format("missing; {}", allowed));
  return *v;
}

std::optional<double> BodyReader::optional_number(const std::string& key, double min, double max,
                                                  const std::string& allowed, bool above_min) {
  const json* v = find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_number()) bad_value(name(key), fmt::format("{} is not a number; {}", shown(*v), allowed));
  const double x = v->get<double>();
  if (!std::isfinite(x) || x < min || x > max || (above_min && x == min))
    bad_value(name(key), fmt::format("{} is not allowed; {}", shown(*v), allowed));
  return x;
}

std::int64_t BodyReader::integer(const std::string& key, std::int64_t min, std::int64_t max) {
  const std::string allowed = fmt::format("a whole number {}..{}", min, max);
  const json& v = require(key, allowed);
  if (!v.is_number_integer()) bad_value(name(key), fmt::format("{} is not allowed; {}", shown(v), allowed));
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(max))
    bad_value(name(key), fmt::format("{} is not allowed; {}", shown(v), allowed));
  const auto x = v.get<std::int64_t>();
  if (x < min || x > max) bad_value(name(key), fmt::format("{} is not allowed; {}", shown(v), allowed));
  return x;
}

std::optional<bool> BodyReader::optional_boolean(const std::string& key) {
  const json* v = find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_boolean()) bad_value(name(key), fmt::format("{} is not allowed; true or false", shown(*v)));
  return v->get<bool>();
}

bool BodyReader::boolean(const std::string& key) {
  auto v = optional_boolean(key);
  if (!v) bad_value(name(key), "missing; true or false");
  return *v;
}

std::optional<std::string> BodyReader::optional_string(const std::string& key, std::size_t max_bytes) {
  const json* v = find(key);
  if (v == nullptr) return std::nullopt;
  if (!v->is_string()) bad_value(name(key), fmt::format("{} is not allowed; a string", shown(*v)));
  const auto& s = v->get_ref<const std::string&>();
  if (s.size() > max_bytes) bad_value(name(key), fmt::format("{} bytes; at most {} are allowed", s.size(), max_bytes));
  return s;
}

std::string BodyReader::string(const std::string& key, std::size_t max_bytes) {
  auto v = optional_string(key, max_bytes);
  if (!v) bad_value(name(key), "missing; a string");
  return *v;
}

std::string BodyReader::word(const std::string& key, const std::vector<std::string>& words) {
  std::string allowed;
  for (const auto& w : words) allowed += (allowed.empty() ? "" : ", ") + ("\"" + w + "\"");
  const json& v = require(key, "one of " + allowed);
  if (v.is_string())
    for (const auto& w : words)
      if (v.get_ref<const std::string&>() == w) return w;
  bad_value(name(key), fmt::format("{} is not allowed; one of {}", shown(v), allowed));
}

void BodyReader::finish() const {
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (known_.count(it.key())) continue;
    std::string allowed;
    for (const auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
    bad_value(name(it.key()), fmt::format("unknown field (allowed here: {})", allowed.empty() ? "none" : allowed));
  }
}

void parse_empty_request(const json& body) { BodyReader(body).finish(); }

ControlRequest parse_control_request(const json& body) {
  BodyReader r(body);
  const auto take = r.optional_boolean("take");
  const auto release = r.optional_boolean("release");
  r.finish();
  if (take.value_or(false) == release.value_or(false) || take == false || release == false)
    throw ApiError(400, "control: give {\"take\": true} to take control or {\"release\": true} to release it");
  return {take.value_or(false)};
}

JointsRequest parse_joints_request(const arm::ArmModel& model, const json& body) {
  BodyReader r(body);
  JointsRequest out;
  out.targets.assign(model.joints.size(), std::nullopt);
  const json& positions = r.require("positions", "an object {\"<joint name>\": value in deg or mm, ...}");
  if (!positions.is_object() || positions.empty())
    bad_value("positions", fmt::format("{} is not allowed; an object with at least one joint: {{\"<joint name>\": value "
                                       "in deg or mm}}, joints: {}",
                                       shown(positions), joint_names(model)));
  for (auto it = positions.begin(); it != positions.end(); ++it) {
    const std::string field = "positions." + it.key();
    const auto index = model.find_joint(it.key());
    if (!index) bad_value(field, fmt::format("arm {} has no such joint; joints: {}", model.name, joint_names(model)));
    const auto& j = model.joints[std::size_t(*index)];
    if (out.targets[std::size_t(*index)]) bad_value(field, fmt::format("joint {} is given twice", j.name));
    const std::string allowed = fmt::format("a number in {} ({})", display_unit(j.dimension), joint_range(j));
    if (!it->is_number()) bad_value(field, fmt::format("{} is not a number; {}", shown(*it), allowed));
    const double shown_value = it->get<double>();
    if (!std::isfinite(shown_value)) bad_value(field, fmt::format("{} is not allowed; {}", shown(*it), allowed));
    // The range against the limits is Arm::check_targets' (the handler's); this is the unit.
    out.targets[std::size_t(*index)] = from_display(j.dimension, shown_value);
  }
  const auto speed = r.optional_number("speed", 0, 1, "a fraction of the joints' velocity limits above 0 up to 1", true);
  const auto duration = r.optional_number(
      "duration", 0, motion::kMaxMoveDuration,
      fmt::format("seconds, above 0 up to {:g} (a time shorter than the joints allow is stretched to it)",
                  motion::kMaxMoveDuration),
      true);
  r.finish();
  if (speed && duration) bad_value("duration", "give speed or duration, not both");
  if (speed) out.speed = *speed;
  out.duration = duration;
  return out;
}

namespace {

// Reads speed (0, 1]; without one, a move gets what every app gives (motion/move_limits.hpp).
double speed_field(BodyReader& r, bool linear) {
  return r.optional_number("speed", 0, 1,
                           "above 0 up to 1: a fraction of the joints' velocity limits (linear: of 200 mm/s)", true)
      .value_or(linear ? motion::kDefaultToolSpeed / kMaxLinearSpeed : motion::kDefaultJointSpeed);
}

// "avoid" (a PTP may go around obstacles) and "avoid_time" (the search's budget): the
// budget when avoiding, else nothing.
std::optional<double> avoid_fields(BodyReader& r) {
  const bool avoid = r.optional_boolean("avoid").value_or(false);
  const std::string budget = fmt::format("s, {:g}..{:g} (with \"avoid\": true; default 1)", arm::kMinAvoidTime, arm::kMaxAvoidTime);
  const auto avoid_time = r.optional_number("avoid_time", arm::kMinAvoidTime, arm::kMaxAvoidTime, budget);
  if (avoid_time && !avoid) bad_value("avoid_time", "is allowed only with \"avoid\": true");
  if (!avoid) return std::nullopt;
  return avoid_time.value_or(arm::AvoidOptions{}.time_budget);
}

}  // namespace

ToolRequest parse_tool_request(const json& body) {
  BodyReader r(body);
  ToolRequest out;
  const double reach_mm = kMaxReach * 1e3;
  const std::string allowed = fmt::format("mm, -{0:g}..{0:g}", reach_mm);
  const char* axes[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) out.position[k] = r.number(axes[k], -reach_mm, reach_mm, allowed) / 1e3;
  const std::string angle = "deg, -360..360 (leave it out to keep the tool's)";
  auto rad = [](std::optional<double> d) { return d ? std::optional(*d * M_PI / 180) : std::nullopt; };
  out.roll = rad(r.optional_number("roll", -360, 360, angle));
  out.pitch = rad(r.optional_number("pitch", -360, 360, angle));
  out.yaw = rad(r.optional_number("yaw", -360, 360, angle));
  out.linear = r.optional_boolean("linear").value_or(false);
  out.speed = speed_field(r, out.linear);
  out.avoid_time = avoid_fields(r);
  if (out.avoid_time && out.linear)
    bad_value("avoid", "true is not allowed with \"linear\": true: a straight line has no detour (avoid is for a PTP move)");
  r.finish();
  return out;
}

JogRequest parse_jog_request(const json& body) {
  BodyReader r(body);
  JogRequest out;
  static const std::vector<std::string> kAxes = {"x", "y", "z", "roll", "pitch", "yaw"};
  const std::string axis = r.word("axis", kAxes);
  for (std::size_t k = 0; k < kAxes.size(); ++k)
    if (kAxes[k] == axis) out.axis = int(k);
  const bool angle = out.axis >= 3;
  const double max = angle ? 90 : kMaxJogLength * 1e3;
  const double step = r.number("step", -max, max,
                               fmt::format("{0} (signed), not 0, -{1:g}..{1:g}", angle ? "deg" : "mm", max));
  if (step == 0) bad_value("step", fmt::format("0 is not allowed; a step of {} that is not 0", angle ? "deg" : "mm"));
  out.step = angle ? step * M_PI / 180 : step / 1e3;
  out.linear = r.optional_boolean("linear").value_or(false);
  out.speed = speed_field(r, out.linear);
  r.finish();
  return out;
}

namespace {

// {"joint": name, "speed": deg/s or mm/s}: one joint at a velocity, the others still.
arm::ServoCommand joint_servo_request(const arm::ArmModel& model, BodyReader& r) {
  const json& name = r.require("joint", fmt::format("a joint's name: {}", joint_names(model)));
  if (!name.is_string())
    bad_value("joint", fmt::format("{} is not allowed; a joint's name: {}", shown(name), joint_names(model)));
  const auto index = model.find_joint(name.get_ref<const std::string&>());
  if (!index)
    bad_value("joint", fmt::format("{}: arm {} has no such joint; joints: {}", shown(name), model.name,
                                   joint_names(model)));
  const auto& j = model.joints[std::size_t(*index)];
  if (j.role == arm::JointRole::gripper)
    bad_value("joint", fmt::format("{} is the gripper: POST /api/v1/gripper moves it", shown(name)));
  // As fast as the joint may go: its velocity limit, in the units people read.
  const double most = to_display(j.dimension, j.limits.velocity);
  const double speed = r.number("speed", -most, most,
                                fmt::format("{0}/s (signed; 0 stops), -{1:g}..{1:g}: joint {2}'s velocity limit",
                                            display_unit(j.dimension), most, j.name));
  r.finish();
  arm::JointVelocities v;
  v.values.assign(model.joints.size(), 0.0);
  v.values[std::size_t(*index)] = from_display(j.dimension, speed);
  return arm::ServoCommand{v, std::nullopt};
}

}  // namespace

arm::ServoCommand parse_servo_request(const arm::ArmModel& model, const json& body) {
  // The keyboard's fastest steps (jog/key_jog.cpp): what a held button may ask.
  constexpr double kMostLinear = 100, kMostAngular = 60;  // mm/s, deg/s
  BodyReader r(body);
  const std::string either =
      "\"axis\" (the tool along or about x, y, z, roll, pitch, yaw) or \"joint\" (one joint by its name)";
  if (!r.has("axis") && !r.has("joint")) bad_value("axis", "missing; give " + either);
  if (r.has("axis") && r.has("joint")) bad_value("joint", "give " + either + ", not both");
  if (r.has("joint")) return joint_servo_request(model, r);
  static const std::vector<std::string> kAxes = {"x", "y", "z", "roll", "pitch", "yaw"};
  const std::string axis = r.word("axis", kAxes);
  int k = 0;
  while (kAxes[std::size_t(k)] != axis) ++k;
  const bool angle = k >= 3;
  const double most = angle ? kMostAngular : kMostLinear;
  const double speed = r.number("speed", -most, most, fmt::format("{0} (signed; 0 stops), -{1:g}..{1:g}",
                                                                  angle ? "deg/s" : "mm/s", most));
  const std::string frame = r.optional_string("frame", 8).value_or("base");
  if (frame != "base" && frame != "tool") bad_value("frame", "'base' or 'tool'");
  r.finish();
  arm::ToolTwist t;
  t.frame = frame == "tool" ? arm::ServoFrame::tool : arm::ServoFrame::base;
  if (angle) t.angular[k - 3] = speed * M_PI / 180;
  else t.linear[k] = speed / 1e3;
  return arm::ServoCommand{t, std::nullopt};
}

double parse_gripper_request(const json& body) {
  BodyReader r(body);
  const double closed = r.number("closed", 0, 1, "how far closed, 0 (open) up to 1 (closed)");
  r.finish();
  return closed;
}

bool parse_torque_request(const json& body) {
  BodyReader r(body);
  const bool on = r.boolean("on");
  r.finish();
  return on;
}

std::string check_point_name(std::string_view name) {
  if (name.empty() || name.size() > files::kPointNameMaxLength)
    bad_value("name", fmt::format("'{}' is not allowed; a letter or '_' then letters, digits or '_', at most {} "
                                  "characters",
                                  printable(name), files::kPointNameMaxLength));
  if (auto why = files::bad_name(name)) bad_value("name", fmt::format("'{}' is not allowed: {}", printable(name), *why));
  return std::string(name);
}

std::string parse_point_request(const json& body) {
  BodyReader r(body);
  const std::string name = r.string("name", 1024);
  r.finish();
  return check_point_name(name);
}

ProgramRequest parse_program_request(const json& body, bool run) {
  BodyReader r(body);
  ProgramRequest out;
  out.source = r.string("source", kMaxBodyBytes);
  out.points = r.optional_string("points", kMaxBodyBytes).value_or("");
  if (run)
    out.speed = r.optional_number("speed", 0, 1, "above 0 up to 1: a fraction of the programmed speeds", true)
                    .value_or(1.0);
  out.avoid_time = avoid_fields(r);
  r.finish();
  return out;
}

}  // namespace armctl::web

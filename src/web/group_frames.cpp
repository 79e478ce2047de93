#include "web/group_frames.hpp"

#include <charconv>
#include <cmath>

#include <fmt/core.h>

#include "arm/group_actions.hpp"
#include "core/printable.hpp"
#include "core/quantity.hpp"
#include "web/display_value.hpp"
#include "files/rob_file.hpp"
#include "protocol/robot_commands/messages.hpp"
#include "web/api_error.hpp"
#include "web/base64.hpp"
#include "web/request_body.hpp"

namespace armctl::web {

namespace {

using json = nlohmann::json;
constexpr auto kRc = arm::Protocol::robot_commands;

// Refused unless the arm can be driven through a Robot Commands board at all.
void require_rc(const arm::ArmModel& model) {
  if (!model.supports(kRc))
    throw ApiError(409, fmt::format("arm {} has no Robot Commands servo map: action groups need a Robot Commands "
                                    "board",
                                    model.name));
}

// The coupled partner of joint `i`, if any.
std::optional<std::size_t> partner(const arm::ArmModel& model, std::size_t i) {
  for (const auto& c : model.couplings) {
    if (std::size_t(c.first) == i) return std::size_t(c.second);
    if (std::size_t(c.second) == i) return std::size_t(c.first);
  }
  return std::nullopt;
}

}  // namespace

GroupFrames frames_to_group(const arm::ArmModel& model, const json& frames) {
  require_rc(model);
  if (!frames.is_array() || frames.empty() || frames.size() > files::kGroupFileMaxActions)
    bad_value("frames", fmt::format("{} is not allowed; an array of 1..{} frames {{\"time_ms\": ..., \"positions\": "
                                    "{{\"<joint name>\": deg or mm}}}}",
                                    shown(frames), files::kGroupFileMaxActions));
  GroupFrames out;
  std::string servo_set;  // the first frame's joints, for the same-servos rule's message
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::string at = fmt::format("frames[{}].", k);
    BodyReader r(frames[k], at);
    const auto time_ms = std::uint16_t(r.integer("time_ms", 0, rc::kMoveTimeMaxMs));
    const json& positions = r.require("positions", "an object {\"<joint name>\": value in deg or mm}");
    r.finish();
    if (!positions.is_object() || positions.empty())
      bad_value(at + "positions", fmt::format("{} is not allowed; an object with at least one joint", shown(positions)));
    std::vector<std::optional<double>> targets(model.joints.size());
    for (auto it = positions.begin(); it != positions.end(); ++it) {
      const std::string field = at + "positions." + it.key();
      const auto index = model.find_joint(it.key());
      if (!index) bad_value(field, fmt::format("arm {} has no such joint", model.name));
      const auto& j = model.joints[std::size_t(*index)];
      if (!j.map(kRc)) bad_value(field, fmt::format("joint {} has no Robot Commands servo", j.name));
      if (targets[std::size_t(*index)]) bad_value(field, fmt::format("joint {} is given twice", j.name));
      if (!it->is_number() || !std::isfinite(it->get<double>()))
        bad_value(field, fmt::format("{} is not allowed; a number in {}", shown(*it), display_unit(j.dimension)));
      targets[std::size_t(*index)] = from_display(j.dimension, it->get<double>());
    }
    for (std::size_t i = 0; i < targets.size(); ++i) {
      if (auto p = partner(model, i); p && targets[i].has_value() != targets[*p].has_value())
        bad_value(at + "positions", fmt::format("joints {} and {} are driven together: give both or neither",
                                                model.joints[i].name, model.joints[*p].name));
    }
    auto action = arm::servo_action(model, targets, time_ms);
    if (!action) bad_value(at + "positions", action.error().message);
    out.group.actions.push_back(std::move(action).value());
    out.targets.push_back(std::move(targets));
  }
  // The group file's own rules (every action the same servos, ...): format and parse it.
  for (const auto& t : out.group.actions.front().targets) out.group.servos.push_back(t.servo);
  auto checked = files::parse_action_group(files::format_action_group(out.group), "frames");
  if (!checked)
    throw ApiError(400, fmt::format("{} (every frame must give the same joints)", checked.error().message));
  out.group = std::move(checked).value();
  return out;
}

json group_to_frames(const arm::ArmModel& model, const files::ActionGroupFile& group) {
  require_rc(model);
  json frames = json::array();
  for (std::size_t k = 0; k < group.actions.size(); ++k) {
    const auto& action = group.actions[k];
    std::vector<double> device(model.joints.size(), 500.0);
    std::vector<bool> given(model.joints.size(), false);
    for (const auto& t : action.targets) {
      std::optional<std::size_t> joint;
      for (std::size_t i = 0; i < model.joints.size(); ++i)
        if (model.joints[i].map(kRc) && model.joints[i].map(kRc)->id == t.servo) joint = i;
      if (!joint) throw ApiError(400, fmt::format("action {}: servo {} is not a joint of arm {}", k + 1, t.servo, model.name));
      if (!t.position) continue;  // keep: left out of the frame
      device[*joint] = *t.position;
      given[*joint] = true;
    }
    for (std::size_t i = 0; i < given.size(); ++i)
      if (auto p = partner(model, i); p && given[i] != given[*p])
        throw ApiError(400, fmt::format("action {}: joints {} and {} are driven together: the group moves one and keeps "
                                        "the other",
                                        k + 1, model.joints[i].name, model.joints[*p].name));
    const std::vector<double> q = model.from_device(kRc, device);
    json positions = json::object();
    for (std::size_t i = 0; i < q.size(); ++i)
      if (given[i]) positions[model.joints[i].name] = display_value(model.joints[i].dimension, q[i]);
    frames.push_back({{"time_ms", action.time_ms}, {"positions", std::move(positions)}});
  }
  return frames;
}

std::uint8_t parse_group_number(std::string_view text) {
  int n = -1;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (text.empty() || text.size() > 3 || ec != std::errc() || end != text.data() + text.size() || n < 0 ||
      n > rc::kGroupMax)
    throw ApiError(400, fmt::format("group '{}' is not allowed; a group number 0..{}", printable(text.substr(0, 20)),
                                    rc::kGroupMax));
  return std::uint8_t(n);
}

std::uint16_t parse_group_run(const json& body) {
  BodyReader r(body);
  const bool has_count = r.has("count");
  const auto continuous = r.optional_boolean("continuous");
  std::uint16_t times = 0;
  if (has_count) times = std::uint16_t(r.integer("count", 1, 65535));
  r.finish();
  if (has_count == continuous.value_or(false) || continuous == false)
    throw ApiError(400, "give {\"count\": N} (1..65535 times) or {\"continuous\": true} (until stopped)");
  return times;
}

std::uint16_t parse_group_speed(const json& body) {
  BodyReader r(body);
  const auto percent = r.integer("percent", rc::kSpeedPercentMin, rc::kSpeedPercentMax);
  r.finish();
  return std::uint16_t(percent);
}

files::ActionGroupFile parse_group_import(const json& body) {
  BodyReader r(body);
  const std::string format = r.word("format", {"group", "rob"});
  const std::string content = r.string("content", kMaxBodyBytes);
  r.finish();
  if (format == "group") return must(files::parse_action_group(content, "content"));
  auto bytes = base64_decode(content);
  if (!bytes) bad_value("content", "not base64: a .rob file's bytes are sent as base64");
  if (bytes->size() > files::kRobMaxBytes)
    bad_value("content", fmt::format("{} bytes; a .rob file has at most {}", bytes->size(), files::kRobMaxBytes));
  return must(files::parse_rob_file(*bytes, "content"));
}

json export_group(const arm::ArmModel& model, const json& body) {
  BodyReader r(body);
  const std::string format = r.word("format", {"group", "rob"});
  const json& frames = r.require("frames", "an array of frames");
  r.finish();
  const GroupFrames g = frames_to_group(model, frames);
  if (format == "group") return {{"content", files::format_action_group(g.group)}};
  return {{"content", base64_encode(must(files::format_rob_file(g.group)))}};
}

}  // namespace armctl::web

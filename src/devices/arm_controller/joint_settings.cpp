#include "devices/arm_controller/joint_settings.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "core/strict_json.hpp"
#include "core/atomic_file.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::arm_controller {

namespace {

using nlohmann::json;

// One problem with the file; parse_settings turns it into the invalid_config error.
struct Refusal {
  std::string what;
};

// A value as it stood in the file, short enough for an error message.
std::string shown(const json& v) {
  std::string text = v.dump(-1, ' ', true, json::error_handler_t::replace);
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

std::string key_text(const std::string& key) { return json(key).dump(-1, ' ', true, json::error_handler_t::replace); }

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// `where` must be an object holding exactly `keys` (the ones save_settings writes): a missing
// key is a truncated file, an unknown one a typo that would otherwise be ignored silently.
void expect_keys(const json& where, const std::string& name, const std::vector<std::string>& keys) {
  if (!where.is_object())
    throw Refusal{fmt::format("{} is {}, not an object with keys {}", name, shown(where), joined(keys))};
  for (const auto& k : keys)
    if (!where.contains(k)) throw Refusal{fmt::format("{} has no key \"{}\" (needs {})", name, k, joined(keys))};
  for (const auto& item : where.items()) {
    bool known = false;
    for (const auto& k : keys) known = known || item.key() == k;
    if (!known)
      throw Refusal{fmt::format("{} has unknown key {} (allowed: {})", name, key_text(item.key()), joined(keys))};
  }
}

// An integer written as one (no 1.0, no true, no "1"), within lo..hi. nlohmann's get<int>
// would truncate 1.9, read true as 1 and wrap 4294967297 to 1.
std::int64_t integer_in(const json& v, const std::string& name, std::int64_t lo, std::int64_t hi,
                        const std::string& allowed) {
  bool ok = false;
  std::int64_t n = 0;
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    ok = u <= static_cast<std::uint64_t>(hi) && hi >= 0;
    n = ok ? static_cast<std::int64_t>(u) : 0;
  } else if (v.is_number_integer()) {
    n = v.get<std::int64_t>();
    ok = true;
  }
  if (!ok || n < lo || n > hi)
    throw Refusal{fmt::format("{} {} is not allowed (allowed: an integer {})", name, shown(v), allowed)};
  return n;
}

std::int64_t integer_in(const json& v, const std::string& name, std::int64_t lo, std::int64_t hi) {
  return integer_in(v, name, lo, hi, fmt::format("{}..{}", lo, hi));
}

void parse_joint(const json& j, const std::string& name, int number, JointSettings& js) {
  expect_keys(j, name, {"saved_offset", "limits"});
  js.saved_offset = static_cast<std::int8_t>(
      integer_in(j.at("saved_offset"), name + ".saved_offset", rc::kOffsetMin, rc::kOffsetMax));
  // The ranges BusServoInfoWrite accepts (rc_board/board.cpp): the controller must read back
  // every file it can write. Positions are Robot Commands units, not clicks: the config's
  // soft limits are applied on top of them (by the core, at import), not here.
  const std::string ln = name + ".limits";
  const json& l = j.at("limits");
  expect_keys(l, ln,
              {"position_min", "position_max", "millivolts_min", "millivolts_max", "temp_max", "led_status",
               "led_warning"});
  rc_board::BusServoLimits& lim = js.limits;
  lim.servo = static_cast<rc_board::ServoId>(number);
  lim.position_min =
      static_cast<std::uint16_t>(integer_in(l.at("position_min"), ln + ".position_min", rc::kPositionMin, rc::kPositionMax));
  lim.position_max = static_cast<std::uint16_t>(
      integer_in(l.at("position_max"), ln + ".position_max", lim.position_min, rc::kPositionMax,
                 fmt::format("position_min ({})..{}", lim.position_min, rc::kPositionMax)));
  lim.millivolts_min = static_cast<std::uint16_t>(
      integer_in(l.at("millivolts_min"), ln + ".millivolts_min", rc::kMillivoltsMin, rc::kMillivoltsMax));
  lim.millivolts_max = static_cast<std::uint16_t>(
      integer_in(l.at("millivolts_max"), ln + ".millivolts_max", lim.millivolts_min, rc::kMillivoltsMax,
                 fmt::format("millivolts_min ({})..{}", lim.millivolts_min, rc::kMillivoltsMax)));
  lim.temp_max =
      static_cast<std::uint16_t>(integer_in(l.at("temp_max"), ln + ".temp_max", rc::kTempMaxMin, rc::kTempMaxMax));
  lim.led_status = static_cast<std::uint8_t>(integer_in(l.at("led_status"), ln + ".led_status", 0, 1,
                                                        "0..1 (0 = enable, 1 = disable)"));
  lim.led_warning = static_cast<std::uint8_t>(
      integer_in(l.at("led_warning"), ln + ".led_warning", 0, 7, "0..7 (bits 0..2)"));
}

ControllerSettings parse_document(std::string_view text, const ControllerSettings& defaults) {
  // A key twice in one object (nlohmann keeps the last) would hide a hand edit.
  Result<json> parsed = parse_strict_json(text, 8);
  if (!parsed) {
    const JsonProblem* problem = parsed.error().detail_as<JsonProblem>();
    if (problem && *problem == JsonProblem::syntax)
      throw Refusal{fmt::format("not readable as settings JSON ({})", parsed.error().message)};
    throw Refusal{parsed.error().message};
  }
  const json doc = std::move(parsed).value();
  expect_keys(doc, "the file", {"version", "info_joint", "joints"});
  integer_in(doc.at("version"), "version", 1, 1, "1 (the only format so far)");
  std::vector<std::string> numbers;  // the joint keys allowed: this arm's joint numbers
  for (const auto& [number, js] : defaults.joints) numbers.push_back(std::to_string(number));
  ControllerSettings s = defaults;
  const json& info = doc.at("info_joint");
  bool info_known = false;
  if (info.is_number_integer())
    for (const auto& [number, js] : defaults.joints) info_known = info_known || info == number;
  if (!info_known)
    throw Refusal{fmt::format("info_joint {} is not a joint of this arm (allowed: {})", shown(info), joined(numbers))};
  s.info_joint = info.get<int>();
  const json& joints = doc.at("joints");
  if (!joints.is_object())
    throw Refusal{fmt::format("joints is {}, not an object keyed by joint number ({})", shown(joints), joined(numbers))};
  for (const auto& item : joints.items()) {
    // Exactly the decimal number of a configured joint: std::stoi read "1abc", " 1" and "01" as 1.
    auto it = s.joints.end();
    for (auto j = s.joints.begin(); j != s.joints.end(); ++j)
      if (item.key() == std::to_string(j->first)) it = j;
    if (it == s.joints.end())
      throw Refusal{fmt::format("joints.{}: not a joint of this arm (allowed keys: {})", key_text(item.key()),
                                joined(numbers))};
    parse_joint(item.value(), "joints." + item.key(), it->first, it->second);
  }
  return s;
}

}  // namespace

std::filesystem::path settings_path(const std::filesystem::path& state_dir) {
  return state_dir / "controller-settings.json";
}

Result<ControllerSettings> parse_settings(std::string_view text, std::string_view source,
                                          const ControllerSettings& defaults) {
  try {
    return parse_document(text, defaults);
  } catch (const Refusal& r) {
    return Error{ErrorKind::invalid_config, fmt::format("{}: {}; fix or delete the file", source, r.what)};
  } catch (const json::exception& e) {
    return Error{ErrorKind::invalid_config,
                 fmt::format("{}: not readable as settings JSON ({}); fix or delete the file", source, e.what())};
  }
}

Result<ControllerSettings> load_settings(const std::filesystem::path& state_dir,
                                         const ControllerSettings& defaults) {
  const auto path = settings_path(state_dir);
  // A few hundred bytes for seven joints; 64 KiB is far above any real one.
  auto bytes = read_whole_file(path, 64 * 1024);
  if (!bytes) return bytes.error();
  if (!bytes->has_value()) return defaults;
  const auto& data = **bytes;
  return parse_settings(std::string_view(reinterpret_cast<const char*>(data.data()), data.size()), path.string(),
                        defaults);
}

Status save_settings(const std::filesystem::path& state_dir, const ControllerSettings& settings) {
  json doc;
  doc["version"] = 1;
  doc["info_joint"] = settings.info_joint;
  json joints = json::object();
  for (const auto& [number, js] : settings.joints) {
    const auto& l = js.limits;
    joints[std::to_string(number)] = {
        {"saved_offset", js.saved_offset},
        {"limits",
         {{"position_min", l.position_min}, {"position_max", l.position_max},
          {"millivolts_min", l.millivolts_min}, {"millivolts_max", l.millivolts_max},
          {"temp_max", l.temp_max}, {"led_status", l.led_status}, {"led_warning", l.led_warning}}}};
  }
  doc["joints"] = joints;
  std::string text = doc.dump(2) + "\n";
  return write_file_atomically(
      settings_path(state_dir),
      std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace armctl::arm_controller

#include "devices/arm_controller/joint_settings.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "devices/rc_board/atomic_file.hpp"

namespace armctl::arm_controller {

namespace {

using nlohmann::json;

Error corrupt(const std::filesystem::path& path, const std::string& what) {
  return Error{ErrorKind::invalid_config, fmt::format("{}: {}", path.string(), what)};
}

}  // namespace

std::filesystem::path settings_path(const std::filesystem::path& state_dir) {
  return state_dir / "controller-settings.json";
}

Result<ControllerSettings> load_settings(const std::filesystem::path& state_dir,
                                         const ControllerSettings& defaults) {
  const auto path = settings_path(state_dir);
  auto bytes = rc_board::read_whole_file(path);
  if (!bytes) return bytes.error();
  if (!bytes->has_value()) return defaults;
  ControllerSettings s = defaults;
  try {
    json doc = json::parse((*bytes)->begin(), (*bytes)->end());
    if (doc.value("version", 0) != 1) return corrupt(path, "version must be 1");
    int info = doc.at("info_joint").get<int>();
    if (!s.joints.count(info)) return corrupt(path, fmt::format("info_joint {} is not a joint of this arm", info));
    s.info_joint = info;
    for (auto& [key, j] : doc.at("joints").items()) {
      int number = std::stoi(key);
      auto it = s.joints.find(number);
      if (it == s.joints.end()) return corrupt(path, fmt::format("joints.{}: not a joint of this arm", key));
      JointSettings& js = it->second;
      int offset = j.at("saved_offset").get<int>();
      if (offset < -125 || offset > 125)
        return corrupt(path, fmt::format("joints.{}.saved_offset {} not in -125..125", key, offset));
      js.saved_offset = static_cast<std::int8_t>(offset);
      const json& l = j.at("limits");
      // `key` is captured through an init-capture: clang before 16 cannot capture a
      // structured binding in a lambda (C++20 P1091), and the fuzz build uses clang 14.
      auto u16 = [&, &joint_key = key](const char* k, int lo, int hi) -> std::uint16_t {
        int v = l.at(k).get<int>();
        if (v < lo || v > hi)
          throw std::out_of_range(fmt::format("joints.{}.limits.{} {} not in {}..{}", joint_key, k, v, lo, hi));
        return static_cast<std::uint16_t>(v);
      };
      js.limits.servo = static_cast<std::uint8_t>(number);
      js.limits.position_min = u16("position_min", 0, 1000);
      js.limits.position_max = u16("position_max", js.limits.position_min, 1000);
      js.limits.millivolts_min = u16("millivolts_min", 4500, 12000);
      js.limits.millivolts_max = u16("millivolts_max", js.limits.millivolts_min, 12000);
      js.limits.temp_max = u16("temp_max", 50, 100);
      js.limits.led_status = static_cast<std::uint8_t>(u16("led_status", 0, 1));
      js.limits.led_warning = static_cast<std::uint8_t>(u16("led_warning", 0, 7));
    }
  } catch (const std::exception& e) {
    return corrupt(path, fmt::format("unreadable settings ({}); fix or delete the file", e.what()));
  }
  return s;
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
  return rc_board::write_file_atomically(
      settings_path(state_dir),
      std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace armctl::arm_controller

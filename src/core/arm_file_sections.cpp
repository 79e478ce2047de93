#include "core/arm_file_sections.hpp"

#include <cstdio>
#include <mutex>
#include <set>
#include <system_error>

#include <fmt/core.h>

#include "core/printable.hpp"

namespace armctl::arm_file {

using json_reader::json;
using json_reader::ObjectReader;

bool is_arm_file(const json& root) { return root.is_object() && root.contains("family") && root.contains("urdf"); }

bool is_arm_file(const std::filesystem::path& path) {
  auto text = read_text_file(path, "arm file", json_reader::kMaxConfigBytes);
  if (!text) return true;
  Result<json> doc = parse_strict_json(*text, json_reader::kMaxConfigDepth);
  return !doc || is_arm_file(*doc);
}

Section read_section(const json& root, std::string_view section, const std::string& source) {
  ObjectReader top(source, root, "");
  const std::string key(section);
  const json& object = top.require(key);
  ObjectReader s(source, object, key);  // an object, or refused
  Section out{&object, key, {}};
  const json* entries = object.contains("joints") ? &object["joints"] : nullptr;
  if (entries != nullptr && !entries->is_object())
    s.fail(s.at("joints"), "must be an object of joint name: settings (the arm's joints are in joints[])");
  const json& joints = top.require("joints");
  if (!joints.is_array()) top.fail("joints", "must be an array of joint objects");
  std::set<std::string> names;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string path = fmt::format("joints[{}]", i);
    const json& j = joints[i];
    if (!j.is_object() || !j.contains("name") || !j["name"].is_string()) top.fail(path + ".name", "must be a string");
    const std::string name = j["name"].get<std::string>();
    names.insert(name);
    if (!j.contains("joint_bus")) continue;
    const json& bus = j["joint_bus"];
    if (!bus.is_object()) top.fail(path + ".joint_bus", "must be an object");
    BusJoint b;
    b.name = name;
    b.number = int(top.integer(bus.contains("number") ? bus["number"] : json(), path + ".joint_bus.number", 1, 7));
    auto number = [&](const char* k) {
      return top.number(bus.contains(k) ? bus[k] : json(), fmt::format("{}.joint_bus.{}", path, k), 1, 1e9);
    };
    b.max_speed_cps = number("max_speed_cps");
    b.max_accel_cps2 = number("max_accel_cps2");
    b.path = fmt::format("{}.joints.{}", key, name);
    b.bus_path = path + ".joint_bus";
    if (entries != nullptr && entries->contains(name)) b.entry = &(*entries)[name];
    out.joints.push_back(std::move(b));
  }
  if (entries != nullptr)
    for (auto it = entries->begin(); it != entries->end(); ++it)
      if (it.key() != "comment" && !names.contains(it.key()))
        s.fail(s.at("joints") + "." + it.key(), "no joint of this arm has this name (see joints[].name)");
  return out;
}

namespace {

struct MovedFile {
  std::string_view old_name;
  std::string_view section;
};
constexpr MovedFile kMovedFiles[] = {{"scara.json", kSimulatorSection}, {"scara-arm.json", kControllerSection}};

}  // namespace

std::filesystem::path moved_config_file(const std::filesystem::path& path) {
  std::error_code ec;
  for (const MovedFile& m : kMovedFiles) {
    if (path.filename() != m.old_name || std::filesystem::exists(path, ec)) continue;
    const std::filesystem::path arm_file = path.parent_path() / kScaraArmFile;
    if (!std::filesystem::exists(arm_file, ec)) return path;  // reading it fails, naming it
    warn_once(fmt::format("{} is now the \"{}\" section of the arm file {}: reading that (pass the arm file "
                          "with --arm)",
                          path.string(), m.section, arm_file.string()));
    return arm_file;
  }
  return path;
}

json load_box_document(const std::filesystem::path& asked, std::string_view section, std::string_view what,
                       std::filesystem::path* path) {
  *path = moved_config_file(asked);
  json doc = json_reader::parse_document(json_reader::read_config_file(*path, what), path->string());
  if (doc.is_object() && !is_arm_file(doc))
    warn_once(fmt::format("{}: {} of the old form, a file of its own (still read); the SCARA's is now the \"{}\" "
                          "section of its arm file, config/{}",
                          path->string(), what, section, kScaraArmFile));
  return doc;
}

void warn_once(const std::string& message) {
  static std::mutex mutex;
  static std::set<std::string> said;
  const std::lock_guard lock(mutex);
  if (!said.insert(message).second) return;
  fmt::print(stderr, "armctl: warning: {}\n", printable(message));
  std::fflush(stderr);
}

}  // namespace armctl::arm_file

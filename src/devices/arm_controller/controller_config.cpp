#include "devices/arm_controller/controller_config.hpp"

#include "core/arm_file_sections.hpp"
#include "core/config_files.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/json_reader.hpp"
#include "portable/joint_tuning.hpp"

namespace armctl::arm_controller {

namespace {

using nlohmann::json;
using armctl::json_reader::ObjectReader;

std::int32_t round_to_int32(double x) {
  return static_cast<std::int32_t>(std::clamp(std::lround(x), -2147483647L, 2147483647L));
}

// One joint from its entry `j` at `path`. Its name, number and velocity and acceleration
// limits come from the entry (a config of the old form) or, from an arm file, from the arm's
// joint (`bus`): there they are not repeated.
ControllerJointConfig parse_joint(const std::string& source, const json& j, std::string path,
                                  const arm_file::BusJoint* bus) {
  ObjectReader r(source, j, path);
  ControllerJointConfig c;
  if (bus == nullptr) {
    const json& name = r.require("name");
    if (!name.is_string() || name.get<std::string>().empty())
      r.fail(r.at("name"), "must be a non-empty string");
    c.name = name.get<std::string>();
    c.number = static_cast<std::uint8_t>(r.integer("number", 1, 7));
  } else {
    c.name = bus->name;
    c.number = static_cast<std::uint8_t>(bus->number);
  }

  {
    ObjectReader m(source, r.require("map"), r.at("map"));
    auto [rc_a, rc_b] = m.pair("rc", 0, 1000);
    auto [cl_a, cl_b] = m.pair("clicks", -32768, 32767);
    if (rc_a == rc_b) m.fail(m.at("rc"), "the two positions must differ (a line needs two points)");
    if (cl_a == cl_b) m.fail(m.at("clicks"), "the two click values must differ");
    m.finish();
    c.map = LinearMap{double(rc_a), double(cl_a), double(rc_b), double(cl_b)};
  }
  auto [lo, hi] = r.pair("soft_limits_clicks", -32768, 32767);
  if (lo >= hi) r.fail(r.at("soft_limits_clicks"), fmt::format("minimum {} must be below maximum {}", lo, hi));
  c.soft_min = static_cast<std::int16_t>(lo);
  c.soft_max = static_cast<std::int16_t>(hi);
  // The same ranges the joint controller accepts (portable/joint_tuning.hpp).
  // Taken from the header, not repeated here: the copies 200000 and 20000000 had drifted
  // from the joint's narrowed limits, so configs the joints would clamp were accepted.
  if (bus == nullptr) {
    c.max_speed_cps = r.number("max_speed_cps", 1, joint_bus::max_speed_cps_limit);
    c.max_accel_cps2 =
        r.number("max_accel_cps2", joint_bus::min_accel_cps2_limit, joint_bus::max_accel_cps2_limit);
  } else {
    c.max_speed_cps = r.number(json(bus->max_speed_cps), bus->bus_path + ".max_speed_cps", 1,
                               joint_bus::max_speed_cps_limit);
    c.max_accel_cps2 = r.number(json(bus->max_accel_cps2), bus->bus_path + ".max_accel_cps2",
                                joint_bus::min_accel_cps2_limit, joint_bus::max_accel_cps2_limit);
  }
  if (const json* z = r.find("zone_clicks"))
    c.zone_clicks = static_cast<std::int16_t>(r.integer(*z, r.at("zone_clicks"), 0, 32767));
  r.finish();
  return c;
}

}  // namespace

std::int32_t LinearMap::to_clicks(double rc) const {
  return round_to_int32(clicks_a + (rc - rc_a) * clicks_per_unit());
}

std::int32_t LinearMap::to_rc(double clicks) const {
  return round_to_int32(rc_a + (clicks - clicks_a) / clicks_per_unit());
}

const ControllerJointConfig* ControllerConfig::joint(int number) const {
  for (const auto& j : joints)
    if (j.number == number) return &j;
  return nullptr;
}

namespace {

// The config `doc` at `top_path` ("" for a config of the old form, "arm_controller" in an arm
// file). `bus_joints` is null for the old form (joints[] holds every joint), else the arm's.
ControllerConfig read_config(const json& doc, const std::string& source, const std::string& top_path,
                             const std::vector<arm_file::BusJoint>* bus_joints) {
  ObjectReader r(source, doc, top_path);
  ControllerConfig config;
  if (const json* mv = r.find("supply_millivolts"))
    config.supply_millivolts = static_cast<std::uint16_t>(r.integer(*mv, r.at("supply_millivolts"), 1, 65535));
  std::vector<std::pair<const json*, std::string>> entries;  // each joint's entry and its path
  if (bus_joints == nullptr) {
    const json& joints = r.require("joints");
    if (!joints.is_array() || joints.empty() || joints.size() > 7)
      r.fail("joints", "must be an array of 1..7 joint objects");
    for (std::size_t i = 0; i < joints.size(); ++i) entries.push_back({&joints[i], fmt::format("joints[{}]", i)});
  } else {
    (void)r.find("joints");  // read by arm_file::read_section
    if (bus_joints->empty() || bus_joints->size() > 7)
      r.fail(r.at("joints"), fmt::format("the arm needs 1..7 joints with a joint_bus mapping, has {}", bus_joints->size()));
    for (const arm_file::BusJoint& b : *bus_joints) {
      if (b.entry == nullptr)
        r.fail(b.path, "missing: every joint on the joint bus needs its map and soft_limits_clicks here");
      if (b.entry->contains("name") || b.entry->contains("number") || b.entry->contains("max_speed_cps") ||
          b.entry->contains("max_accel_cps2"))
        r.fail(b.path, "name, number, max_speed_cps and max_accel_cps2 are the arm's (joints[].name, "
                       "joints[].joint_bus), not repeated here");
      entries.push_back({b.entry, b.path});
    }
  }
  std::set<int> numbers;
  std::set<std::string> names;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string& path = entries[i].second;
    ControllerJointConfig j = parse_joint(source, *entries[i].first, path, bus_joints ? &(*bus_joints)[i] : nullptr);
    if (!numbers.insert(j.number).second)
      r.fail(path + ".number", fmt::format("joint number {} appears twice (each of 1..7 at most once)", j.number));
    if (!names.insert(j.name).second)
      r.fail(path + ".name", fmt::format("joint name \"{}\" appears twice", j.name));
    config.joints.push_back(std::move(j));
  }
  r.finish();
  std::sort(config.joints.begin(), config.joints.end(),
            [](const auto& a, const auto& b) { return a.number < b.number; });
  return config;
}

}  // namespace

ControllerConfig parse_controller_config(std::string_view json_text, const std::string& source) {
  return arm_file::parse_box_config(json_text, arm_file::kControllerSection, source, read_config);
}

ControllerConfig load_controller_config(const std::filesystem::path& path) {
  return arm_file::load_box_config(path, arm_file::kControllerSection, "arm controller config", read_config);
}

std::filesystem::path default_controller_config_path() { return find_config_file(arm_file::kScaraArmFile); }

}  // namespace armctl::arm_controller

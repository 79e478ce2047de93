#include "devices/arm_controller/controller_config.hpp"

#include "core/config_files.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "portable/joint_tuning.hpp"

namespace armctl::arm_controller {

namespace {

using nlohmann::json;

std::int32_t round_to_int32(double x) {
  return static_cast<std::int32_t>(std::clamp(std::lround(x), -2147483647L, 2147483647L));
}

// Reads one JSON object, refusing unknown keys; errors carry "<source>: <path>: ...".
class ObjectReader {
 public:
  ObjectReader(const std::string& source, const json& object, std::string path)
      : source_(source), object_(object), path_(std::move(path)) {
    if (!object_.is_object()) fail(path_, "must be an object");
  }

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: {}: {}", source_, path, what));
  }
  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  const json* find(const std::string& key) {
    known_.insert(key);
    auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
  }
  const json& require(const std::string& key) {
    const json* v = find(key);
    if (v == nullptr) fail(at(key), "missing");
    return *v;
  }

  double number(const json& v, const std::string& path, double min, double max) const {
    if (!v.is_number()) fail(path, fmt::format("must be a number in {}..{}", min, max));
    double x = v.get<double>();
    if (!std::isfinite(x) || x < min || x > max)
      fail(path, fmt::format("{} is outside the allowed range {}..{}", x, min, max));
    return x;
  }
  std::int64_t integer(const json& v, const std::string& path, std::int64_t min,
                       std::int64_t max) const {
    if (!v.is_number_integer()) fail(path, fmt::format("must be a whole number in {}..{}", min, max));
    // Above INT64_MAX the value is stored unsigned and get<int64_t> would wrap it negative,
    // so the message would name a number the file does not contain.
    if (v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(max))
      fail(path, fmt::format("{} is outside the allowed range {}..{}", v.get<std::uint64_t>(), min, max));
    auto x = v.get<std::int64_t>();
    if (x < min || x > max) fail(path, fmt::format("{} is outside the allowed range {}..{}", x, min, max));
    return x;
  }
  double number(const std::string& key, double min, double max) {
    return number(require(key), at(key), min, max);
  }
  std::int64_t integer(const std::string& key, std::int64_t min, std::int64_t max) {
    return integer(require(key), at(key), min, max);
  }
  // A two-element array [a, b] of whole numbers in min..max.
  std::pair<std::int64_t, std::int64_t> pair(const std::string& key, std::int64_t min,
                                             std::int64_t max) {
    const json& v = require(key);
    if (!v.is_array() || v.size() != 2)
      fail(at(key), fmt::format("must be an array of two whole numbers in {}..{}", min, max));
    return {integer(v[0], at(key) + "[0]", min, max), integer(v[1], at(key) + "[1]", min, max)};
  }

  // Refuses every key that was not read (except "comment").
  void finish() const {
    for (auto it = object_.begin(); it != object_.end(); ++it) {
      if (it.key() == "comment" || known_.count(it.key())) continue;
      std::string allowed;
      for (const auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
      fail(at(it.key()), fmt::format("unknown key (allowed here: comment, {})", allowed));
    }
  }

 private:
  const std::string& source_;
  const json& object_;
  std::string path_;
  std::set<std::string> known_;
};

ControllerJointConfig parse_joint(const std::string& source, const json& j, std::string path) {
  ObjectReader r(source, j, path);
  ControllerJointConfig c;
  const json& name = r.require("name");
  if (!name.is_string() || name.get<std::string>().empty())
    r.fail(r.at("name"), "must be a non-empty string");
  c.name = name.get<std::string>();
  c.number = static_cast<std::uint8_t>(r.integer("number", 1, 7));

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
  c.max_speed_cps = r.number("max_speed_cps", 1, joint_bus::max_speed_cps_limit);
  c.max_accel_cps2 =
      r.number("max_accel_cps2", joint_bus::min_accel_cps2_limit, joint_bus::max_accel_cps2_limit);
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

ControllerConfig parse_controller_config(std::string_view json_text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::exception& e) {
    // json::exception, not only parse_error: a number too large for a double ("1e400") is
    // an out_of_range from the parser (found by fuzz_controller_config), and must not escape.
    throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: not valid JSON: {}", source, e.what()));
  }
  ObjectReader r(source, doc, "");
  ControllerConfig config;
  if (const json* mv = r.find("supply_millivolts"))
    config.supply_millivolts = static_cast<std::uint16_t>(r.integer(*mv, "supply_millivolts", 1, 65535));
  const json& joints = r.require("joints");
  if (!joints.is_array() || joints.empty() || joints.size() > 7)
    r.fail("joints", "must be an array of 1..7 joint objects");
  std::set<int> numbers;
  std::set<std::string> names;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    std::string path = fmt::format("joints[{}]", i);
    ControllerJointConfig j = parse_joint(source, joints[i], path);
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

ControllerConfig load_controller_config(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in)
    throw ArmctlError(ErrorKind::io, fmt::format("cannot open arm config {}", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_controller_config(text.str(), path.string());
}

std::filesystem::path default_controller_config_path() { return find_config_file("scara-arm.json"); }

}  // namespace armctl::arm_controller

#include "devices/joint_sim/arm_config.hpp"

#include "core/arm_file_sections.hpp"
#include "core/config_files.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/json_reader.hpp"

namespace armctl::joint_sim {

namespace {

using nlohmann::json;

std::string type_name(const json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number_integer() || v.is_number_unsigned()) return "an integer";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  return "an object";
}

std::string format_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// Reads the keys of one config object. A joint's value comes from its own entry
// (`primary`) or, if absent there, from joint_defaults (`fallback`); errors name the path
// the value really came from. Every key read is recorded so finish() can refuse the rest.
class Reader {
 public:
  Reader(const std::string& source, const json* primary, std::string primary_path,
         const json* fallback, std::string fallback_path)
      : source_(source),
        primary_(primary),
        fallback_(fallback),
        primary_path_(std::move(primary_path)),
        fallback_path_(std::move(fallback_path)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw ArmctlError(ErrorKind::invalid_config, source_ + ": " + path + ": " + what);
  }

  // The value for `key` and its path, or nullptr if neither object has it.
  const json* find(const std::string& key, std::string* path) {
    known_.push_back(key);
    if (primary_ != nullptr && primary_->contains(key)) {
      *path = join(primary_path_, key);
      return &(*primary_)[key];
    }
    if (fallback_ != nullptr && fallback_->contains(key)) {
      *path = join(fallback_path_, key);
      return &(*fallback_)[key];
    }
    *path = join(primary_path_, key);
    return nullptr;
  }

  const json& require(const std::string& key, std::string* path) {
    const json* v = find(key, path);
    if (v == nullptr) {
      fail(*path, "missing (set it here" +
                      (fallback_path_.empty() ? std::string() : " or in " + fallback_path_) + ")");
    }
    return *v;
  }

  double number(const std::string& key, double min, double max, const char* unit,
                bool min_exclusive = false) {
    std::string path;
    const json& v = require(key, &path);
    if (!v.is_number()) fail(path, "expected a number, got " + type_name(v));
    const double x = v.get<double>();
    const bool low = min_exclusive ? !(x > min) : !(x >= min);
    if (low || !(x <= max) || !std::isfinite(x)) {
      fail(path, format_number(x) + " is out of range (allowed: " +
                     (min_exclusive ? "> " : "") + format_number(min) + " .. " +
                     format_number(max) + " " + unit + ")");
    }
    return x;
  }

  // A PID gain. The joint controller holds gains in Q8 (steps of 1/256), so a non-zero value
  // that would round to 0 is refused instead of silently switching its term off.
  std::int32_t gain_q8(const std::string& key, const char* unit) {
    const double x = number(key, 0.0, 255.0, unit);
    const auto q = static_cast<std::int32_t>(std::lround(x * 256.0));
    if (x > 0.0 && q == 0) {
      std::string path;
      find(key, &path);
      fail(path, format_number(x) +
                     " is below the joint controller's resolution of 1/256 (allowed: 0 to switch "
                     "the term off, or 0.0039 .. 255 " + unit + ")");
    }
    return q;
  }

  std::int64_t integer(const std::string& key, std::int64_t min, std::int64_t max,
                       const char* unit) {
    std::string path;
    const json& v = require(key, &path);
    return checked_integer(v, path, min, max, unit);
  }

  std::int64_t checked_integer(const json& v, const std::string& path, std::int64_t min,
                               std::int64_t max, const char* unit) const {
    if (!v.is_number_integer() && !v.is_number_unsigned()) {
      fail(path, "expected an integer, got " + type_name(v));
    }
    if (v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(max)) {
      fail(path, std::to_string(v.get<std::uint64_t>()) + " is out of range (allowed: " +
                     std::to_string(min) + " .. " + std::to_string(max) + " " + unit + ")");
    }
    const std::int64_t x = v.get<std::int64_t>();
    if (x < min || x > max) {
      fail(path, std::to_string(x) + " is out of range (allowed: " + std::to_string(min) +
                     " .. " + std::to_string(max) + " " + unit + ")");
    }
    return x;
  }

  std::string string(const std::string& key, std::size_t max_length) {
    std::string path;
    const json& v = require(key, &path);
    if (!v.is_string()) fail(path, "expected a string, got " + type_name(v));
    const std::string s = v.get<std::string>();
    if (s.empty() || s.size() > max_length) {
      fail(path, "\"" + s + "\" has the wrong length (allowed: 1.." +
                     std::to_string(max_length) + " characters)");
    }
    return s;
  }

  // A nested object: a Reader over the same key in both objects.
  Reader object(const std::string& key) {
    known_.push_back(key);
    const json* p = child(primary_, key, primary_path_);
    const json* f = child(fallback_, key, fallback_path_);
    if (p == nullptr && f == nullptr) {
      fail(join(primary_path_, key), "missing (an object is required" +
                                         (fallback_path_.empty() ? std::string()
                                                                 : " here or in " + fallback_path_) +
                                         ")");
    }
    return Reader(source_, p, join(primary_path_, key), f,
                  fallback_path_.empty() ? std::string() : join(fallback_path_, key));
  }

  // Refuse keys nobody read ("comment" is always allowed, for notes in the file).
  void finish() const {
    check_unknown(primary_, primary_path_);
    check_unknown(fallback_, fallback_path_);
  }

  const std::string& path() const { return primary_path_; }

 private:
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  const json* child(const json* parent, const std::string& key, const std::string& path) const {
    if (parent == nullptr || !parent->contains(key)) return nullptr;
    const json& v = (*parent)[key];
    if (!v.is_object()) fail(join(path, key), "expected an object, got " + type_name(v));
    return &v;
  }

  void check_unknown(const json* obj, const std::string& path) const {
    if (obj == nullptr) return;
    for (const auto& [key, value] : obj->items()) {
      if (key == "comment") {
        if (!value.is_string()) fail(join(path, key), "expected a string, got " + type_name(value));
        continue;
      }
      if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
      std::string allowed;
      for (const std::string& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
      fail(join(path, key), "unknown key (allowed: " + allowed + ", comment)");
    }
  }

  const std::string& source_;
  const json* primary_;
  const json* fallback_;
  std::string primary_path_;
  std::string fallback_path_;
  std::vector<std::string> known_;
};

void read_motor(Reader r, MotorParams* m) {
  m->supply_v = r.number("supply_v", 0.0, 60.0, "V", true);
  m->resistance_ohm = r.number("resistance_ohm", 0.01, 100.0, "ohm");
  m->torque_constant_nm_per_a = r.number("torque_constant_nm_per_a", 0.001, 5.0, "N*m/A");
  m->rotor_inertia_kgm2 = r.number("rotor_inertia_kgm2", 1e-8, 1.0, "kg*m^2");
  m->viscous_friction_nms = r.number("viscous_friction_nms", 0.0, 1.0, "N*m*s/rad");
  m->coulomb_friction_nm = r.number("coulomb_friction_nm", 0.0, 10.0, "N*m");
  r.finish();
}

// One joint's hardware and tuning from `entry` at `path` (over `defaults` at
// `defaults_path`). Its name and number come from the entry (a config of the old form) or,
// from an arm file, from the arm's joint (`bus`): there they are not repeated.
JointConfig read_joint(const std::string& source, const json& entry, const std::string& path, const json* defaults,
                       const std::string& defaults_path, std::uint32_t physics_step_us,
                       const arm_file::BusJoint* bus) {
  Reader r(source, &entry, path, defaults, defaults ? defaults_path : "");
  JointConfig j;
  if (bus == nullptr) {
    j.name = r.string("name", 32);
    j.number = static_cast<std::uint8_t>(r.integer("number", 1, 7, "(the joint's select line)"));
  } else {
    j.name = bus->name;
    j.number = static_cast<std::uint8_t>(bus->number);
  }
  JointHardwareParams& h = j.hardware;
  read_motor(r.object("motor"), &h.motor);
  {
    Reader g = r.object("gearbox");
    h.gear_numerator = static_cast<std::uint32_t>(g.integer("numerator", 1, 1000000, ""));
    h.gear_denominator = static_cast<std::uint32_t>(g.integer("denominator", 1, 1000000, ""));
    g.finish();
  }
  h.encoder_lines_per_rev =
      static_cast<std::uint32_t>(r.integer("encoder_lines_per_rev", 1, 100000, "lines"));
  h.load_inertia_kgm2 = r.number("load_inertia_kgm2", 0.0, 1000.0, "kg*m^2");
  {
    std::string stops_path;
    const json* stops = r.find("end_stops_clicks", &stops_path);
    if (stops != nullptr && !stops->is_null()) {
      if (!stops->is_array() || stops->size() != 2) {
        r.fail(stops_path, "expected null or [min, max] in clicks, got " + type_name(*stops));
      }
      const auto lo = static_cast<std::int32_t>(
          r.checked_integer((*stops)[0], stops_path + "[0]", -32768, 0, "clicks"));
      const auto hi = static_cast<std::int32_t>(
          r.checked_integer((*stops)[1], stops_path + "[1]", 0, 32767, "clicks"));
      if (lo >= hi) {
        r.fail(stops_path, "min must be below max (the joint starts at 0 between them)");
      }
      h.end_stops = EndStops{lo, hi};
    }
  }
  h.step = std::chrono::microseconds(physics_step_us);

  Reader t = r.object("tuning");
  h.pwm_max = static_cast<std::int16_t>(t.integer("pwm_max", 1, 4095, "PWM counts"));
  j.tuning.pwm_max = h.pwm_max;
  // The velocity limit must be reachable: below the motor's no-load speed.
  const double no_load_cps = h.motor.supply_v / h.motor.torque_constant_nm_per_a *
                             h.clicks_per_motor_rev() / (2.0 * std::numbers::pi);
  const auto speed_cap =
      std::clamp<std::int64_t>(std::int64_t(no_load_cps), 1, joint_bus::max_speed_cps_limit);
  // The joint controller's own limits (portable/joint_tuning.hpp; PositionLoop::begin clamps
  // into them): the wider 1000..5e7 used here before let values through that the joint then
  // silently replaced (found by fuzz_arm_config).
  if (bus == nullptr) {
    j.tuning.max_speed_cps = static_cast<std::int32_t>(
        t.integer("max_speed_cps", 1, speed_cap, "clicks/s, below the motor's no-load speed"));
    j.tuning.max_accel_cps2 = static_cast<std::int32_t>(t.integer(
        "max_accel_cps2", joint_bus::min_accel_cps2_limit, joint_bus::max_accel_cps2_limit, "clicks/s^2"));
  } else {
    // The arm's joint_bus.max_speed_cps / max_accel_cps2: the planner's limits are the joint's tuning.
    const std::string& from = bus->bus_path;
    auto whole = [&](double v, const char* key, double min, double max, const char* unit) {
      if (!(v >= min && v <= max) || v != std::floor(v))
        r.fail(from + "." + key, format_number(v) + " is out of range (allowed: whole numbers " + format_number(min) +
                                     " .. " + format_number(max) + " " + unit + ")");
      return static_cast<std::int32_t>(v);
    };
    j.tuning.max_speed_cps =
        whole(bus->max_speed_cps, "max_speed_cps", 1, double(speed_cap), "clicks/s, below the motor's no-load speed");
    j.tuning.max_accel_cps2 = whole(bus->max_accel_cps2, "max_accel_cps2", joint_bus::min_accel_cps2_limit,
                                    joint_bus::max_accel_cps2_limit, "clicks/s^2");
  }
  j.tuning.kp_q8 = t.gain_q8("kp", "PWM counts per click");
  j.tuning.ki_q8 = t.gain_q8("ki", "PWM counts per click per ms");
  j.tuning.kd_q8 = t.gain_q8("kd", "PWM counts per click/ms");
  t.finish();
  r.finish();
  return j;
}

}  // namespace

const JointConfig& ArmConfig::joint(int number) const {
  for (const JointConfig& j : joints) {
    if (j.number == number) return j;
  }
  throw ArmctlError(ErrorKind::invalid_argument,
                    "arm config: no joint number " + std::to_string(number));
}

namespace {

// The config at `top_path` of `root` ("" for a config of the old form, "simulator" in an arm
// file): baud, physics step, joint_defaults, and one entry per joint. `bus_joints` is null for
// the old form (joints[] holds every joint with its name and number), else the arm's joints.
ArmConfig read_config(const json& root, const std::string& source, const std::string& top_path,
                      const std::vector<arm_file::BusJoint>* bus_joints) {
  Reader top(source, &root, top_path, nullptr, "");
  ArmConfig config;
  config.baud = static_cast<std::uint32_t>(top.integer("baud", 300, 2000000, "baud"));
  const auto step_us =
      static_cast<std::uint32_t>(top.integer("physics_step_us", 1, 1000, "microseconds"));

  std::string path;
  const json* defaults = top.find("joint_defaults", &path);
  if (defaults != nullptr && !defaults->is_object()) {
    top.fail(path, "expected an object, got " + type_name(*defaults));
  }
  if (defaults != nullptr && (defaults->contains("name") || defaults->contains("number"))) {
    top.fail(path, "name and number belong to each joint, not to the defaults");
  }
  const std::string defaults_path = path;
  std::vector<std::pair<const json*, std::string>> entries;  // each joint's entry and its path
  static const json kEmpty = json::object();
  if (bus_joints == nullptr) {
    const json& joints = top.require("joints", &path);
    if (!joints.is_array() || joints.empty() || joints.size() > 7) {
      top.fail(path, "expected an array of 1..7 joints, got " + type_name(joints) +
                         (joints.is_array() ? " of " + std::to_string(joints.size()) : ""));
    }
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const std::string jpath = "joints[" + std::to_string(i) + "]";
      if (!joints[i].is_object()) top.fail(jpath, "expected an object, got " + type_name(joints[i]));
      entries.push_back({&joints[i], jpath});
    }
  } else {
    (void)top.find("joints", &path);  // read by arm_file::read_section
    if (bus_joints->empty() || bus_joints->size() > 7)
      top.fail(path, "the arm needs 1..7 joints with a joint_bus mapping to be simulated, has " +
                         std::to_string(bus_joints->size()));
    for (const arm_file::BusJoint& b : *bus_joints) {
      if (b.entry != nullptr && !b.entry->is_object()) top.fail(b.path, "expected an object, got " + type_name(*b.entry));
      if (b.entry != nullptr && (b.entry->contains("name") || b.entry->contains("number")))
        top.fail(b.path, "name and number are the arm's (joints[].name, joints[].joint_bus.number), not repeated here");
      entries.push_back({b.entry != nullptr ? b.entry : &kEmpty, b.path});
    }
  }
  top.finish();

  std::set<int> numbers;
  std::set<std::string> names;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string& jpath = entries[i].second;
    JointConfig j = read_joint(source, *entries[i].first, jpath, defaults, defaults_path, step_us,
                               bus_joints ? &(*bus_joints)[i] : nullptr);
    if (!numbers.insert(j.number).second) {
      top.fail(jpath + ".number", std::to_string(j.number) + " is used twice (allowed: each of 1..7 once)");
    }
    if (!names.insert(j.name).second) {
      top.fail(jpath + ".name", "\"" + j.name + "\" is used twice (names must be unique)");
    }
    config.joints.push_back(std::move(j));
  }
  std::sort(config.joints.begin(), config.joints.end(),
            [](const JointConfig& a, const JointConfig& b) { return a.number < b.number; });
  return config;
}

}  // namespace

ArmConfig parse_arm_config(std::string_view json_text, const std::string& source) {
  return arm_file::parse_box_config(json_text, arm_file::kSimulatorSection, source, read_config);
}

ArmConfig load_arm_config(const std::filesystem::path& path) {
  return arm_file::load_box_config(path, arm_file::kSimulatorSection, "simulator config", read_config);
}

std::filesystem::path default_arm_config_path() { return find_config_file(arm_file::kScaraArmFile); }

}  // namespace armctl::joint_sim

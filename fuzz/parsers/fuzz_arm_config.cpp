// The simulated arm's config parser (devices/joint_sim/arm_config.hpp) on hostile input.
// Input byte 0 chooses the mode: even = the rest is the JSON text itself; odd = the rest
// chooses edits to config/scara.arm.json (its simulator section; json_edits.hpp). Either way the parser must throw
// ArmctlError(invalid_config) with a message naming the source, or return a config whose
// every value lies in the documented ranges (the tuning is checked by handing it to the
// joint controller's PositionLoop, which must not need to clamp anything).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <set>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "json_edits.hpp"
#include "portable/position_loop.hpp"

namespace {

using armctl::joint_sim::ArmConfig;

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz_arm_config: accepted config breaks: %s\n", what);
  std::abort();
}

void check(bool ok, const char* what) {
  if (!ok) broken(what);
}

bool in(double x, double lo, double hi) { return std::isfinite(x) && x >= lo && x <= hi; }

void check_config(const ArmConfig& c) {
  check(c.baud >= 300 && c.baud <= 2000000, "baud 300..2000000");
  check(!c.joints.empty() && c.joints.size() <= 7, "1..7 joints");
  std::set<std::string> names;
  int last_number = 0;
  for (const auto& j : c.joints) {
    check(j.number >= 1 && j.number <= 7, "joint number 1..7");
    check(j.number > last_number, "joints sorted by number, each number once");
    last_number = j.number;
    check(!j.name.empty() && j.name.size() <= 32, "name 1..32 characters");
    check(names.insert(j.name).second, "names unique");
    const auto& h = j.hardware;
    const auto& m = h.motor;
    check(in(m.supply_v, 0, 60) && m.supply_v > 0, "supply_v in (0, 60]");
    check(in(m.resistance_ohm, 0.01, 100), "resistance_ohm");
    check(in(m.torque_constant_nm_per_a, 0.001, 5), "torque_constant_nm_per_a");
    check(in(m.rotor_inertia_kgm2, 1e-8, 1), "rotor_inertia_kgm2");
    check(in(m.viscous_friction_nms, 0, 1), "viscous_friction_nms");
    check(in(m.coulomb_friction_nm, 0, 10), "coulomb_friction_nm");
    check(h.gear_numerator >= 1 && h.gear_numerator <= 1000000, "gear numerator");
    check(h.gear_denominator >= 1 && h.gear_denominator <= 1000000, "gear denominator");
    check(h.encoder_lines_per_rev >= 1 && h.encoder_lines_per_rev <= 100000, "encoder lines");
    check(in(h.load_inertia_kgm2, 0, 1000), "load_inertia_kgm2");
    if (h.end_stops) {
      check(h.end_stops->min_clicks < 0 || h.end_stops->min_clicks == 0, "end stop min <= 0");
      check(h.end_stops->max_clicks >= 0, "end stop max >= 0");
      check(h.end_stops->min_clicks < h.end_stops->max_clicks, "end stops min < max");
      check(h.end_stops->min_clicks >= -32768 && h.end_stops->max_clicks <= 32767,
            "end stops within the joint's int16 position");
    }
    check(h.step.count() >= 1000 && h.step.count() <= 1000000, "physics step 1..1000 us");
    check(std::isfinite(h.total_inertia_kgm2()) && h.total_inertia_kgm2() > 0, "inertia");
    // The joint controller itself is the judge of the tuning: PositionLoop::begin() clamps
    // what it does not accept, so an accepted config must come through it unchanged.
    const auto& t = j.tuning;
    armctl::joint_bus::PositionLoop loop;
    loop.begin(t, 0);
    const auto& u = loop.tuning();
    check(u.max_speed_cps == t.max_speed_cps, "max_speed_cps outside what the joint accepts");
    check(u.max_accel_cps2 == t.max_accel_cps2, "max_accel_cps2 outside what the joint accepts");
    check(u.kp_q8 == t.kp_q8 && u.ki_q8 == t.ki_q8 && u.kd_q8 == t.kd_q8,
          "gains outside what the joint accepts");
    check(u.pwm_max == t.pwm_max && t.pwm_max == h.pwm_max, "pwm_max outside what the joint accepts");
    const double no_load_cps = m.supply_v / m.torque_constant_nm_per_a *
                               h.clicks_per_motor_rev() / (2.0 * std::numbers::pi);
    check(t.max_speed_cps <= std::max(1.0, no_load_cps), "max_speed_cps below no-load speed");
  }
}

const std::string& base_text() {
  static const std::string text =
      armctl::fuzz::read_text_file(std::string(ARMCTL_SOURCE_DIR) + "/config/scara.arm.json");
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text = armctl::fuzz::config_text_from(data, size, base_text());
  try {
    const ArmConfig c = armctl::joint_sim::parse_arm_config(text, "fuzz.json");
    check_config(c);
    // Parsing is a pure function of the text.
    const ArmConfig again = armctl::joint_sim::parse_arm_config(text, "fuzz.json");
    check(again.joints.size() == c.joints.size() && again.baud == c.baud, "deterministic");
  } catch (const armctl::ArmctlError& e) {
    if (e.error().kind != armctl::ErrorKind::invalid_config) broken("error kind is not invalid_config");
    if (std::string_view(e.what()).find("fuzz.json") == std::string_view::npos) {
      broken("error message does not name the source");
    }
  }
  // Any other exception escapes and libFuzzer reports it as a crash: the parser must not
  // leak library exceptions (nlohmann::json, std::) to its callers.
  return 0;
}

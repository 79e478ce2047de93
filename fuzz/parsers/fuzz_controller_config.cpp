// The arm controller's config parser (devices/arm_controller/controller_config.hpp) on
// hostile input. Byte 0 chooses the mode: even = the rest is the JSON text; odd = the rest
// chooses edits to config/scara.arm.json (its arm_controller section; json_edits.hpp). The parser must throw
// ArmctlError(invalid_config) naming the source, or return a config whose every value lies
// in the documented ranges, with maps that convert both ways without overflow.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "devices/arm_controller/controller_config.hpp"
#include "json_edits.hpp"
#include "portable/joint_tuning.hpp"

namespace {

using armctl::arm_controller::ControllerConfig;

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_controller_config: accepted config breaks: %s\n", what);
  std::abort();
}

void check_config(const ControllerConfig& c) {
  check(c.supply_millivolts >= 1, "supply_millivolts 1..65535");
  check(!c.joints.empty() && c.joints.size() <= 7, "1..7 joints");
  std::set<std::string> names;
  int last_number = 0;
  for (const auto& j : c.joints) {
    check(j.number >= 1 && j.number <= 7, "joint number 1..7");
    check(j.number > last_number, "joints sorted by number, each number once");
    last_number = j.number;
    check(c.joint(j.number) == &j, "joint() finds each joint");
    check(!j.name.empty(), "name non-empty");
    check(names.insert(j.name).second, "names unique");
    const auto& m = j.map;
    check(m.rc_a >= 0 && m.rc_a <= 1000 && m.rc_b >= 0 && m.rc_b <= 1000, "map.rc in 0..1000");
    check(m.rc_a != m.rc_b, "map.rc points differ");
    check(m.clicks_a >= -32768 && m.clicks_a <= 32767 && m.clicks_b >= -32768 &&
              m.clicks_b <= 32767 && m.clicks_a != m.clicks_b,
          "map.clicks in int16, points differ");
    check(std::isfinite(m.clicks_per_unit()) && m.clicks_per_unit() != 0, "map slope");
    check(j.soft_min < j.soft_max, "soft limits min < max");
    // What the joints accept (portable/joint_tuning.hpp): the planner must not assume more.
    check(std::isfinite(j.max_speed_cps) && j.max_speed_cps >= 1 &&
              j.max_speed_cps <= armctl::joint_bus::max_speed_cps_limit,
          "max_speed_cps within the joint's limit");
    check(std::isfinite(j.max_accel_cps2) && j.max_accel_cps2 >= armctl::joint_bus::min_accel_cps2_limit &&
              j.max_accel_cps2 <= armctl::joint_bus::max_accel_cps2_limit,
          "max_accel_cps2 within the joint's limits");
    check(j.zone_clicks >= 0, "zone_clicks 0..32767");
    // The map must convert every position and every soft limit without overflow (UBSan
    // watches the arithmetic), and positions must come back from clicks.
    for (int rc : {0, 500, 1000}) {
      const std::int32_t clicks = m.to_clicks(rc);
      if (std::abs(m.clicks_per_unit()) >= 1.0) {
        check(m.to_rc(clicks) == rc, "rc -> clicks -> rc round trip");
      }
    }
    (void)m.to_rc(j.soft_min);
    (void)m.to_rc(j.soft_max);
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
    check_config(armctl::arm_controller::parse_controller_config(text, "fuzz.json"));
  } catch (const armctl::ArmctlError& e) {
    check(e.error().kind == armctl::ErrorKind::invalid_config, "error kind is invalid_config");
    check(std::string_view(e.what()).find("fuzz.json") != std::string_view::npos,
          "error message names the source");
  }
  // Any other exception escapes and libFuzzer reports it as a crash.
  return 0;
}

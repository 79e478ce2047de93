// Regressions found by fuzz/parsers/fuzz_arm_config: a number too large for a double
// escaped as a nlohmann exception, and max_accel_cps2 accepted values (1000..5e7) the joint
// controller then silently clamped to its own limits (portable/joint_tuning.hpp).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "portable/joint_tuning.hpp"

namespace armctl::joint_sim {
namespace {

using nlohmann::json;

json config_with_accel(std::int64_t accel) {
  json j = json::parse(R"({
    "baud": 9600, "physics_step_us": 1000,
    "joints": [{"name": "Z", "number": 1,
      "motor": {"supply_v": 24, "resistance_ohm": 1.5, "torque_constant_nm_per_a": 0.075,
                "rotor_inertia_kgm2": 6e-5, "viscous_friction_nms": 2e-5, "coulomb_friction_nm": 0.01},
      "gearbox": {"numerator": 2448, "denominator": 121},
      "encoder_lines_per_rev": 125, "load_inertia_kgm2": 0.02,
      "tuning": {"max_speed_cps": 12000, "max_accel_cps2": 40000, "kp": 12, "ki": 0,
                 "kd": 40, "pwm_max": 255}}]
  })");
  j["joints"][0]["tuning"]["max_accel_cps2"] = accel;
  return j;
}

std::string error_of(const std::string& text) {
  try {
    parse_arm_config(text, "fuzz.json");
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::invalid_config);
    return e.what();
  }
  return "";
}

TEST(ArmConfigFuzzRegression, NumberTooLargeForADoubleIsAConfigError) {
  const std::string e = error_of(R"({"baud": 1e400})");
  EXPECT_NE(e.find("fuzz.json: not valid JSON"), std::string::npos) << e;
  EXPECT_NE(error_of(R"({"joints": [{"load_inertia_kgm2": -1e999}]})"), "");
}

TEST(ArmConfigFuzzRegression, MaxAccelOutsideTheJointControllersRangeIsRefused) {
  const std::int64_t lo = joint_bus::min_accel_cps2_limit;
  const std::int64_t hi = joint_bus::max_accel_cps2_limit;
  for (std::int64_t bad : {std::int64_t{1000}, lo - 1, hi + 1, std::int64_t{50000000}}) {
    const std::string e = error_of(config_with_accel(bad).dump());
    EXPECT_NE(e.find("joints[0].tuning.max_accel_cps2"), std::string::npos) << e;
    EXPECT_NE(e.find(std::to_string(lo) + " .. " + std::to_string(hi)), std::string::npos) << e;
  }
  for (std::int64_t good : {lo, hi}) {
    EXPECT_EQ(parse_arm_config(config_with_accel(good).dump()).joint(1).tuning.max_accel_cps2, good);
  }
}

}  // namespace
}  // namespace armctl::joint_sim

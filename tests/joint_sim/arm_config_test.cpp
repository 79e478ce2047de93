// The simulator section of config/scara.arm.json loads, and every kind of bad config (of the
// old form, a file of its own: the same reader) is refused with a clear message.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "devices/joint_sim/arm_config.hpp"

namespace armctl::joint_sim {
namespace {

using nlohmann::json;

json default_json() {
  return json::parse(R"({
    "baud": 9600, "physics_step_us": 50,
    "joint_defaults": {
      "motor": {"supply_v": 24, "resistance_ohm": 1.5, "torque_constant_nm_per_a": 0.075,
                "rotor_inertia_kgm2": 6e-5, "viscous_friction_nms": 2e-5,
                "coulomb_friction_nm": 0.01},
      "gearbox": {"numerator": 2448, "denominator": 121},
      "encoder_lines_per_rev": 125, "load_inertia_kgm2": 0.02, "end_stops_clicks": null,
      "tuning": {"max_speed_cps": 12000, "max_accel_cps2": 40000, "kp": 12, "ki": 0,
                 "kd": 40, "pwm_max": 255}
    },
    "joints": [{"name": "Z", "number": 1, "end_stops_clicks": [-100, 100]},
               {"name": "SHOULDER", "number": 2, "motor": {"resistance_ohm": 3}}]
  })");
}

// The error message for a config, or "" if it loads.
std::string error_of(const json& j) {
  try {
    parse_arm_config(j.dump(), "test.json");
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::invalid_config);
    return e.what();
  }
  return "";
}

void expect_error(const json& j, const std::string& part1, const std::string& part2) {
  const std::string e = error_of(j);
  EXPECT_NE(e.find(part1), std::string::npos) << e;
  EXPECT_NE(e.find(part2), std::string::npos) << e;
}

TEST(ArmConfig, ShippedScaraConfigHasTheSevenJoints) {
  const ArmConfig c = load_arm_config(default_arm_config_path());
  ASSERT_EQ(c.joints.size(), 7u);
  const char* names[] = {"Z", "SHOULDER", "UAE", "UAJ", "SKE", "SKF", "SKG"};
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(c.joints[i].name, names[i]);
    EXPECT_EQ(c.joints[i].number, i + 1);
    EXPECT_EQ(c.joints[i].hardware.gear_numerator, 2448u);
    EXPECT_EQ(c.joints[i].hardware.gear_denominator, 121u);
  }
  EXPECT_EQ(c.baud, 9600u);
}

TEST(ArmConfig, DefaultsMergeWithPerJointOverrides) {
  const ArmConfig c = parse_arm_config(default_json().dump());
  EXPECT_DOUBLE_EQ(c.joint(1).hardware.motor.resistance_ohm, 1.5);
  EXPECT_DOUBLE_EQ(c.joint(2).hardware.motor.resistance_ohm, 3.0);
  EXPECT_DOUBLE_EQ(c.joint(2).hardware.motor.supply_v, 24.0);  // rest of motor from defaults
  ASSERT_TRUE(c.joint(1).hardware.end_stops);
  EXPECT_EQ(c.joint(1).hardware.end_stops->max_clicks, 100);
  EXPECT_FALSE(c.joint(2).hardware.end_stops);
  EXPECT_EQ(c.joint(1).tuning.kp_q8, 12 * 256);
  EXPECT_EQ(c.joint(1).hardware.step, std::chrono::microseconds(50));
}

TEST(ArmConfig, UnknownKeysAreNamedWithTheAllowedOnes) {
  json j = default_json();
  j["joints"][1]["motor"]["resistanc_ohm"] = 2;
  expect_error(j, "joints[1].motor.resistanc_ohm: unknown key", "resistance_ohm");
  j = default_json();
  j["joint_defaults"]["colour"] = "red";
  expect_error(j, "joint_defaults.colour: unknown key", "allowed:");
  j = default_json();
  j["bauds"] = 1;
  expect_error(j, "bauds: unknown key", "baud");
}

TEST(ArmConfig, WrongTypesAreNamed) {
  json j = default_json();
  j["baud"] = "fast";
  expect_error(j, "baud: expected an integer", "string");
  j = default_json();
  j["joint_defaults"]["motor"]["supply_v"] = true;
  expect_error(j, "joint_defaults.motor.supply_v: expected a number", "boolean");
  j = default_json();
  j["joints"][0]["tuning"] = 5;
  expect_error(j, "joints[0].tuning: expected an object", "integer");
  j = default_json();
  j["joints"][0]["end_stops_clicks"] = "none";
  expect_error(j, "joints[0].end_stops_clicks", "expected null or [min, max]");
}

TEST(ArmConfig, OutOfRangeValuesNameWhatIsAllowed) {
  json j = default_json();
  j["joints"][0]["motor"] = {{"resistance_ohm", 0}};
  expect_error(j, "joints[0].motor.resistance_ohm: 0 is out of range", "allowed: 0.01 .. 100");
  j = default_json();
  j["joints"][1]["number"] = 8;
  expect_error(j, "joints[1].number: 8 is out of range", "1 .. 7");
  j = default_json();
  j["physics_step_us"] = 0;
  expect_error(j, "physics_step_us", "allowed: 1 .. 1000");
  j = default_json();
  j["joint_defaults"]["tuning"]["max_speed_cps"] = 90000;  // faster than the motor can turn
  expect_error(j, "max_speed_cps: 90000 is out of range", "no-load speed");
  j = default_json();
  j["joints"][0]["end_stops_clicks"] = {10, 100};
  expect_error(j, "end_stops_clicks[0]: 10 is out of range", "-32768 .. 0");
  j = default_json();
  j["joint_defaults"]["tuning"]["ki"] = 0.001;  // rounds to 0 in Q8: would silently mean "off"
  expect_error(j, "joint_defaults.tuning.ki: 0.001 is below the joint controller's resolution",
               "0.0039 .. 255");
}

TEST(ArmConfig, MissingDuplicateAndMalformedAreRefused) {
  json j = default_json();
  j["joint_defaults"]["motor"].erase("coulomb_friction_nm");
  expect_error(j, "joints[0].motor.coulomb_friction_nm: missing", "joint_defaults");
  j = default_json();
  j["joints"][1]["number"] = 1;
  expect_error(j, "joints[1].number: 1 is used twice", "once");
  j = default_json();
  j["joints"][1]["name"] = "Z";
  expect_error(j, "joints[1].name", "used twice");
  j = default_json();
  j["joints"] = json::array();
  expect_error(j, "joints: expected an array of 1..7 joints", "array");
  j = default_json();
  j["joint_defaults"]["number"] = 3;
  expect_error(j, "joint_defaults", "belong to each joint");
  try {
    parse_arm_config("{\"baud\": ", "broken.json");
    ADD_FAILURE() << "broken JSON accepted";
  } catch (const ArmctlError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json: not valid JSON"), std::string::npos);
  }
  EXPECT_THROW(load_arm_config("/nonexistent/scara.json"), ArmctlError);
  EXPECT_EQ(error_of(default_json()), "");
}

}  // namespace
}  // namespace armctl::joint_sim

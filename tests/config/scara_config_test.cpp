// config/scara.arm.json is the SCARA's one file: the simulator and the arm controller read
// their sections of it, and a value they share (a joint's name, bus number, velocity and
// acceleration limits) is written once. The old files (config/scara.json, config/scara-arm.json,
// kept in tests/config as they were) gave the same values, and their names still load, with a
// warning naming the arm file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "arm/arm_model.hpp"
#include "core/error.hpp"
#include "devices/arm_controller/controller_config.hpp"
#include "devices/joint_sim/arm_config.hpp"

namespace armctl {
namespace {

const std::filesystem::path kConfigDir = std::filesystem::path(ARMCTL_SOURCE_DIR) / "config";
const std::filesystem::path kOldDir = std::filesystem::path(ARMCTL_SOURCE_DIR) / "tests" / "config";

// Every value of a simulator config, one line per joint.
std::string describe(const joint_sim::ArmConfig& c) {
  std::string out = fmt::format("baud {}\n", c.baud);
  for (const auto& j : c.joints) {
    const auto& h = j.hardware;
    const auto& m = h.motor;
    out += fmt::format(
        "{} #{}: motor {} {} {} {} {} {} gear {}/{} lines {} load {} stops {} pwm {} step {}us tuning {} {} {} {} {} {}\n",
        j.name, j.number, m.supply_v, m.resistance_ohm, m.torque_constant_nm_per_a, m.rotor_inertia_kgm2,
        m.viscous_friction_nms, m.coulomb_friction_nm, h.gear_numerator, h.gear_denominator, h.encoder_lines_per_rev,
        h.load_inertia_kgm2,
        h.end_stops ? fmt::format("{}..{}", h.end_stops->min_clicks, h.end_stops->max_clicks) : std::string("none"),
        h.pwm_max, std::chrono::duration_cast<std::chrono::microseconds>(h.step).count(), j.tuning.max_speed_cps,
        j.tuning.max_accel_cps2, j.tuning.kp_q8, j.tuning.ki_q8, j.tuning.kd_q8, j.tuning.pwm_max);
  }
  return out;
}

std::string describe(const arm_controller::ControllerConfig& c) {
  std::string out = fmt::format("supply {} mV\n", c.supply_millivolts);
  for (const auto& j : c.joints)
    out += fmt::format("{} #{}: map {}:{} {}:{} soft {}..{} speed {} accel {} zone {}\n", j.name, j.number, j.map.rc_a,
                       j.map.clicks_a, j.map.rc_b, j.map.clicks_b, j.soft_min, j.soft_max, j.max_speed_cps,
                       j.max_accel_cps2, j.zone_clicks);
  return out;
}

TEST(ScaraConfig, TheArmFileGivesTheSimulatorWhatTheOldFileDid) {
  const std::string old_form = describe(joint_sim::load_arm_config(kOldDir / "scara.json"));
  EXPECT_EQ(describe(joint_sim::load_arm_config(kConfigDir / "scara.arm.json")), old_form);
  EXPECT_EQ(describe(joint_sim::load_arm_config(joint_sim::default_arm_config_path())), old_form);
  EXPECT_EQ(joint_sim::default_arm_config_path().filename(), "scara.arm.json");
}

TEST(ScaraConfig, TheArmFileGivesTheControllerWhatTheOldFileDid) {
  const std::string old_form = describe(arm_controller::load_controller_config(kOldDir / "scara-arm.json"));
  EXPECT_EQ(describe(arm_controller::load_controller_config(kConfigDir / "scara.arm.json")), old_form);
  EXPECT_EQ(describe(arm_controller::load_controller_config(arm_controller::default_controller_config_path())),
            old_form);
}

TEST(ScaraConfig, TheOldNamesStillLoadAndSayWhereTheValuesAreNow) {
  testing::internal::CaptureStderr();
  const auto sim = joint_sim::load_arm_config(kConfigDir / "scara.json");
  const auto controller = arm_controller::load_controller_config(kConfigDir / "scara-arm.json");
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_EQ(describe(sim), describe(joint_sim::load_arm_config(kOldDir / "scara.json")));
  EXPECT_EQ(describe(controller), describe(arm_controller::load_controller_config(kOldDir / "scara-arm.json")));
  EXPECT_NE(said.find("scara.json is now the \"simulator\" section of the arm file"), std::string::npos) << said;
  EXPECT_NE(said.find("scara-arm.json is now the \"arm_controller\" section of the arm file"), std::string::npos)
      << said;
  EXPECT_NE(said.find("scara.arm.json"), std::string::npos) << said;
}

TEST(ScaraConfig, TheArmModelReadsTheSameFile) {
  auto model = arm::load_arm_model(arm::arm_file_path("scara"));
  ASSERT_TRUE(model) << model.error().message;
  const auto sim = joint_sim::load_arm_config(arm::arm_file_path("scara"));
  ASSERT_EQ(sim.joints.size(), model->joints.size());
  for (std::size_t i = 0; i < sim.joints.size(); ++i) {
    const auto* bus = model->joints[i].map(arm::Protocol::joint_bus);
    ASSERT_TRUE(bus);
    EXPECT_EQ(sim.joints[i].name, model->joints[i].name);
    EXPECT_EQ(sim.joints[i].tuning.max_speed_cps, bus->max_speed_cps);
  }
}

nlohmann::json arm_file() {
  std::ifstream in(kConfigDir / "scara.arm.json");
  return nlohmann::json::parse(in);
}

std::string sim_error(const nlohmann::json& doc) {
  try {
    joint_sim::parse_arm_config(doc.dump(), "arm.json");
  } catch (const ArmctlError& e) {
    return e.what();
  }
  return "accepted";
}

std::string controller_error(const nlohmann::json& doc) {
  try {
    arm_controller::parse_controller_config(doc.dump(), "arm.json");
  } catch (const ArmctlError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ScaraConfig, TheSectionsRefuseRepeatsAndNamesNoJointHas) {
  auto doc = arm_file();
  doc["simulator"]["joints"]["WRIST"] = nlohmann::json::object();
  EXPECT_EQ(sim_error(doc), "arm.json: simulator.joints.WRIST: no joint of this arm has this name (see joints[].name)");

  doc = arm_file();
  doc["simulator"]["joints"]["Z"]["number"] = 1;
  EXPECT_NE(sim_error(doc).find("simulator.joints.Z: name and number are the arm's"), std::string::npos);

  doc = arm_file();
  doc["simulator"]["joints"]["Z"]["tuning"] = {{"max_speed_cps", 100}};
  EXPECT_NE(sim_error(doc).find("simulator.joints.Z.tuning.max_speed_cps: unknown key"), std::string::npos)
      << sim_error(doc);

  doc = arm_file();
  doc["arm_controller"]["joints"]["UAE"]["max_speed_cps"] = 12000;
  EXPECT_NE(controller_error(doc).find("arm_controller.joints.UAE: name, number, max_speed_cps and max_accel_cps2 "
                                       "are the arm's"),
            std::string::npos);

  doc = arm_file();
  doc["arm_controller"]["joints"].erase("SKG");
  EXPECT_NE(controller_error(doc).find("arm_controller.joints.SKG: missing"), std::string::npos);

  doc = arm_file();
  doc.erase("simulator");
  EXPECT_EQ(sim_error(doc), "arm.json: simulator: missing");

  // The shared values are the arm's joint_bus ones: changed there, both boxes see it.
  doc = arm_file();
  doc["joints"][1]["joint_bus"]["max_speed_cps"] = 7000;
  EXPECT_EQ(joint_sim::parse_arm_config(doc.dump(), "arm.json").joint(2).tuning.max_speed_cps, 7000);
  EXPECT_EQ(arm_controller::parse_controller_config(doc.dump(), "arm.json").joint(2)->max_speed_cps, 7000);
}

}  // namespace
}  // namespace armctl

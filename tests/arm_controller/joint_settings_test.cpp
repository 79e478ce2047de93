// The controller's persisted settings (devices/arm_controller/joint_settings.hpp) are outside
// input: a hand-edited or corrupt file must be refused whole, naming the file, the key and
// what is allowed; never read leniently (std::stoi took "1abc" as joint 1, get<int> took
// 1.9, true and 4294967297) and never half-applied.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "controller_rig.hpp"
#include "core/error.hpp"
#include "devices/arm_controller/joint_settings.hpp"

namespace armctl::test {
namespace {

using arm_controller::ControllerSettings;
using arm_controller::JointSettings;
using arm_controller::testing::Rig;
using arm_controller::testing::TempDir;
using nlohmann::json;

// The defaults for an arm whose config has joints 1, 2, 3 and 5 (what the import starts from).
ControllerSettings defaults() {
  ControllerSettings s;
  for (int n : {1, 2, 3, 5}) {
    JointSettings js;
    js.limits.servo = static_cast<std::uint8_t>(n);
    s.joints[n] = js;
  }
  s.info_joint = 1;
  return s;
}

ControllerSettings changed() {
  ControllerSettings s = defaults();
  s.info_joint = 5;
  s.joints[2].saved_offset = -125;
  s.joints[3].saved_offset = 125;
  auto& l = s.joints[5].limits;
  l.position_min = 100;
  l.position_max = 900;
  l.millivolts_min = 6000;
  l.millivolts_max = 8000;
  l.temp_max = 50;
  l.led_status = 1;
  l.led_warning = 7;
  return s;
}

// The text save_settings writes for `s`, as a document to edit.
json saved_document(const ControllerSettings& s) {
  TempDir dir;
  EXPECT_TRUE(arm_controller::save_settings(dir.path, s).ok());
  std::FILE* f = std::fopen(arm_controller::settings_path(dir.path).c_str(), "r");
  json doc = json::parse(f);
  std::fclose(f);
  return doc;
}

std::string refusal(const std::string& text) {
  auto r = arm_controller::parse_settings(text, "settings.json", defaults());
  if (r.ok()) return "";
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_config) << r.error().message;
  EXPECT_EQ(r.error().message.rfind("settings.json: ", 0), 0u) << r.error().message;
  return r.error().message;
}

std::string refusal(const json& doc) { return refusal(doc.dump()); }
std::string refusal(const char* text) { return refusal(std::string(text)); }

#define EXPECT_REFUSED_SAYING(text, ...)                                            \
  do {                                                                              \
    const std::string message_ = refusal(text);                                     \
    ASSERT_NE(message_, "") << "accepted";                                          \
    for (const char* part_ : {__VA_ARGS__})                                         \
      EXPECT_NE(message_.find(part_), std::string::npos) << "missing \"" << part_ << "\" in: " << message_; \
  } while (0)

TEST(JointSettings, WhatTheControllerSavesLoadsBackEqual) {
  TempDir dir;
  ASSERT_TRUE(arm_controller::save_settings(dir.path, changed()).ok());
  auto loaded = arm_controller::load_settings(dir.path, defaults());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(*loaded, changed());
}

TEST(JointSettings, NoFileGivesTheDefaultsAndJointsMissingFromTheFileKeepThem) {
  TempDir dir;
  auto none = arm_controller::load_settings(dir.path, defaults());
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(*none, defaults());
  json doc = saved_document(changed());
  doc["joints"].erase("2");
  auto r = arm_controller::parse_settings(doc.dump(), "settings.json", defaults());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->joints.at(2), defaults().joints.at(2));
  EXPECT_EQ(r->joints.at(3), changed().joints.at(3));
}

TEST(JointSettings, JointKeysMustBeExactlyAJointNumberOfTheArm) {
  const json good = saved_document(changed());
  for (const char* key : {"1abc", " 1", "1 ", "01", "+1", "1.0", "4", "8", "0", "-1", "", "99999999999"}) {
    SCOPED_TRACE(key);
    json doc = good;
    doc["joints"][key] = good["joints"]["1"];
    EXPECT_REFUSED_SAYING(doc, "joints.\"", "not a joint of this arm", "allowed keys: 1, 2, 3, 5");
  }
}

TEST(JointSettings, ValuesOutsideWhatTheControllerAllowsAreRefusedNamingKeyAndRange) {
  const json good = saved_document(changed());
  struct Case {
    const char* pointer;
    json value;
    const char* allowed;
  };
  const std::vector<Case> cases = {
      {"/joints/2/saved_offset", 126, "-125..125"},
      {"/joints/2/saved_offset", -126, "-125..125"},
      {"/joints/2/saved_offset", 1.5, "-125..125"},
      {"/joints/2/saved_offset", true, "-125..125"},
      {"/joints/2/saved_offset", "3", "-125..125"},
      {"/joints/2/saved_offset", 4294967297LL, "-125..125"},
      {"/joints/2/saved_offset", std::numeric_limits<std::uint64_t>::max(), "-125..125"},
      {"/joints/5/limits/position_min", 1001, "0..1000"},
      {"/joints/5/limits/position_min", -1, "0..1000"},
      {"/joints/5/limits/position_max", 99, "position_min (100)..1000"},
      {"/joints/5/limits/position_max", 65536 + 500, "position_min (100)..1000"},
      {"/joints/5/limits/millivolts_min", 4499, "4500..12000"},
      {"/joints/5/limits/millivolts_max", 5999, "millivolts_min (6000)..12000"},
      {"/joints/5/limits/millivolts_max", 12001, "millivolts_min (6000)..12000"},
      {"/joints/5/limits/temp_max", 49, "50..100"},
      {"/joints/5/limits/temp_max", 101, "50..100"},
      {"/joints/5/limits/led_status", 2, "0..1"},
      {"/joints/5/limits/led_warning", 8, "0..7"},
      {"/joints/5/limits/led_warning", nullptr, "0..7"},
      {"/version", 2, "an integer 1 (the only format so far)"},
      {"/version", 1.0, "an integer 1 (the only format so far)"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.pointer) + " = " + c.value.dump());
    json doc = good;
    doc[json::json_pointer(c.pointer)] = c.value;
    std::string key = std::string(c.pointer).substr(1);
    for (auto& ch : key) ch = ch == '/' ? '.' : ch;
    EXPECT_REFUSED_SAYING(doc, key.c_str(), c.allowed, "not allowed");
  }
}

TEST(JointSettings, InfoJointMustBeAJointOfTheArm) {
  const json good = saved_document(changed());
  for (const json& v : {json(4), json(8), json("5"), json(5.0), json(nullptr)}) {
    SCOPED_TRACE(v.dump());
    json doc = good;
    doc["info_joint"] = v;
    EXPECT_REFUSED_SAYING(doc, "info_joint", "not a joint of this arm (allowed: 1, 2, 3, 5)");
  }
}

TEST(JointSettings, MissingUnknownAndDuplicateKeysAreRefused) {
  const json good = saved_document(changed());
  json doc = good;
  doc["joints"]["3"].erase("limits");
  EXPECT_REFUSED_SAYING(doc, "joints.3 has no key \"limits\"");
  doc = good;
  doc["joints"]["3"]["limits"].erase("temp_max");
  EXPECT_REFUSED_SAYING(doc, "joints.3.limits has no key \"temp_max\"");
  doc = good;
  doc["joints"]["3"]["saved_ofset"] = 3;
  EXPECT_REFUSED_SAYING(doc, "joints.3 has unknown key \"saved_ofset\"", "allowed: saved_offset, limits");
  doc = good;
  doc.erase("version");
  EXPECT_REFUSED_SAYING(doc, "no key \"version\"");
  doc = good;
  doc["joints"] = json::array();
  EXPECT_REFUSED_SAYING(doc, "joints is [], not an object");
  doc = good;
  doc["joints"]["5"]["limits"] = 7;
  EXPECT_REFUSED_SAYING(doc, "joints.5.limits is 7, not an object");
  // Two entries for joint 2: which one did the editor mean?
  EXPECT_REFUSED_SAYING(
      R"({"version": 1, "info_joint": 1, "joints": {"2": {"saved_offset": 1, "limits": {}}, "2": {}}})",
      "key \"2\" appears twice");
  EXPECT_REFUSED_SAYING("[1, 2]", "the file is [1,2], not an object");
  EXPECT_REFUSED_SAYING(good.dump().substr(0, 40), "not readable as settings JSON");
  EXPECT_REFUSED_SAYING("", "not readable as settings JSON");
}

TEST(JointSettings, OneBadJointRefusesTheWholeFile) {
  // Joint 2 valid and changed, joint 5 bad: nothing of joint 2 may be taken.
  json doc = saved_document(changed());
  doc["joints"]["5"]["limits"]["temp_max"] = 101;
  TempDir dir;
  std::FILE* f = std::fopen(arm_controller::settings_path(dir.path).c_str(), "w");
  std::fputs(doc.dump().c_str(), f);
  std::fclose(f);
  auto r = arm_controller::load_settings(dir.path, defaults());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_config);
  EXPECT_NE(r.error().message.find(arm_controller::settings_path(dir.path).string()), std::string::npos)
      << r.error().message;
  EXPECT_NE(r.error().message.find("joints.5.limits.temp_max 101"), std::string::npos) << r.error().message;
}

// The earlier implementation's settings file, to be imported at the first start on the core.
TEST(JointSettings, TheControllerRefusesToStartOnAKeyThatOnlyLooksLikeAJoint) {
  TempDir dir;
  std::FILE* f = std::fopen(arm_controller::settings_path(dir.path).c_str(), "w");
  std::fputs(R"({"version": 1, "info_joint": 1, "joints": {"1abc": {"saved_offset": 5, "limits": {}}}})", f);
  std::fclose(f);
  try {
    Rig rig(dir.path);
    FAIL() << "started with a settings file keyed \"1abc\"";
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::invalid_config);
    EXPECT_NE(std::string(e.what()).find("controller-settings.json: joints.\"1abc\": not a joint of this arm"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path / arm_controller::CoreDevice::memory_file)) << "nothing created: the next start imports";
}

}  // namespace
}  // namespace armctl::test

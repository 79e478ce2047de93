#include "devices/arm_controller/controller_config.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace armctl::arm_controller {
namespace {

const std::string kJoint = R"({"name": "Z", "number": 1, "map": {"rc": [0, 1000], "clicks": [-20000, 20000]},
   "soft_limits_clicks": [-15000, 20000], "max_speed_cps": 12000, "max_accel_cps2": 40000})";
const std::string kGood = "{\"joints\": [" + kJoint + "]}";

std::string error_of(const std::string& text) {
  try {
    parse_controller_config(text, "arm.json");
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::invalid_config);
    return e.what();
  }
  return "";
}

std::string with(const std::string& from, const std::string& to) {
  std::string s = kGood;
  auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

TEST(ControllerConfig, ShippedConfigLoads) {
  ControllerConfig c = load_controller_config(default_controller_config_path());
  ASSERT_EQ(c.joints.size(), 7u);
  EXPECT_EQ(c.joints[1].name, "SHOULDER");
  EXPECT_EQ(c.joints[0].map.to_clicks(500), 0);
  EXPECT_EQ(c.joints[0].map.to_rc(20000), 1000);
}

TEST(ControllerConfig, GoodTextParses) {
  ControllerConfig c = parse_controller_config(kGood);
  EXPECT_EQ(c.joints[0].soft_min, -15000);
  EXPECT_EQ(c.supply_millivolts, 24000);
}

TEST(ControllerConfig, ErrorsNameTheKeyAndWhatIsAllowed) {
  EXPECT_NE(error_of(with("\"number\": 1", "\"number\": 9")).find("joints[0].number: 9 is outside the allowed range 1..7"), std::string::npos);
  EXPECT_NE(error_of(with("\"name\": \"Z\",", "\"name\": \"Z\", \"speed\": 3,")).find("joints[0].speed: unknown key"), std::string::npos);
  EXPECT_NE(error_of(with("[-15000, 20000]", "[20000, -15000]")).find("joints[0].soft_limits_clicks"), std::string::npos);
  EXPECT_NE(error_of(with("\"rc\": [0, 1000]", "\"rc\": [5, 5]")).find("joints[0].map.rc"), std::string::npos);
  EXPECT_NE(error_of(with("\"max_speed_cps\": 12000", "\"max_speed_cps\": \"fast\"")).find("joints[0].max_speed_cps: must be a number"), std::string::npos);
  EXPECT_NE(error_of(with("\"max_accel_cps2\": 40000", "\"max_accel_cps2\": 10")).find("3906"), std::string::npos);
  EXPECT_NE(error_of(with(", \"max_accel_cps2\": 40000", "")).find("joints[0].max_accel_cps2: missing"), std::string::npos);
  EXPECT_NE(error_of("{\"joints\": []}").find("joints: must be an array of 1..7"), std::string::npos);
  EXPECT_NE(error_of("{nope").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of("{\"joints\": [" + kJoint + ", " + kJoint + "]}").find("joints[1].number: joint number 1 appears twice"), std::string::npos);
}

}  // namespace
}  // namespace armctl::arm_controller

// Regressions found by fuzz/parsers/fuzz_controller_config: a number too large for a
// double escaped as a nlohmann exception instead of an invalid_config error; and a whole
// number above INT64_MAX was reported as a negative number the file does not contain.
// Also: the velocity and acceleration ranges are the joint controller's own
// (portable/joint_tuning.hpp), no longer copies that had drifted from them.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "devices/arm_controller/controller_config.hpp"
#include "portable/joint_tuning.hpp"

namespace armctl::arm_controller {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_controller_config(text, "fuzz.json");
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::invalid_config);
    return e.what();
  }
  return "";
}

TEST(ControllerConfigFuzzRegression, NumberTooLargeForADoubleIsAConfigError) {
  const std::string e = error_of(R"({"joints": [{"max_speed_cps": 1e400}]})");
  EXPECT_NE(e.find("fuzz.json: not valid JSON"), std::string::npos) << e;
}

TEST(ControllerConfigFuzzRegression, HugeWholeNumberIsNamedAsWritten) {
  const std::string e = error_of(R"({"supply_millivolts": 18446744073709551615, "joints": []})");
  EXPECT_NE(e.find("supply_millivolts: 18446744073709551615 is outside the allowed range 1..65535"),
            std::string::npos)
      << e;
}

std::string joint_with(const std::string& speed, const std::string& accel) {
  return R"({"joints": [{"name": "Z", "number": 1, "map": {"rc": [0, 1000], "clicks": [-20000, 20000]},
    "soft_limits_clicks": [-15000, 20000], "max_speed_cps": )" + speed + R"(, "max_accel_cps2": )" + accel + "}]}";
}

TEST(ControllerConfigFuzzRegression, SpeedAndAccelerationWithinWhatTheJointsAccept) {
  const auto s = [](std::int64_t v) { return std::to_string(v); };
  const std::int64_t vmax = joint_bus::max_speed_cps_limit;
  const std::int64_t amin = joint_bus::min_accel_cps2_limit, amax = joint_bus::max_accel_cps2_limit;
  EXPECT_EQ(error_of(joint_with(s(vmax), s(amin))), "");
  EXPECT_EQ(error_of(joint_with("1", s(amax))), "");
  EXPECT_NE(error_of(joint_with(s(vmax + 1), "40000")).find("max_speed_cps"), std::string::npos);
  EXPECT_NE(error_of(joint_with("12000", s(amax + 1))).find("max_accel_cps2"), std::string::npos);
  EXPECT_NE(error_of(joint_with("12000", s(amin - 1))).find("max_accel_cps2"), std::string::npos);
}

}  // namespace
}  // namespace armctl::arm_controller

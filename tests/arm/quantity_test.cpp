#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/quantity.hpp"

namespace armctl {
namespace {

TEST(Quantity, UnitsConvertToSi) {
  EXPECT_NEAR(*parse_quantity("30deg", Dimension::angle, "j"), std::numbers::pi / 6, 1e-15);
  EXPECT_DOUBLE_EQ(*parse_quantity("-0.5rad", Dimension::angle, "j"), -0.5);
  EXPECT_DOUBLE_EQ(*parse_quantity("120mm", Dimension::length, "j"), 0.12);
  EXPECT_DOUBLE_EQ(*parse_quantity("+0.12m", Dimension::length, "j"), 0.12);
  EXPECT_DOUBLE_EQ(*parse_quantity("2e-3m", Dimension::length, "j"), 0.002);
  EXPECT_NEAR(*parse_quantity("90deg/s", Dimension::angle, "v", 1), std::numbers::pi / 2, 1e-15);
  EXPECT_DOUBLE_EQ(*parse_quantity("300mm/s^2", Dimension::length, "a", 2), 0.3);
  EXPECT_DOUBLE_EQ(*parse_quantity("7", Dimension::length, "x", 0, "mm"), 0.007);
}

TEST(Quantity, BadTextIsRefusedWithWhatIsAllowed) {
  auto wrong_dim = parse_quantity("30mm", Dimension::angle, "joint SHOULDER");
  ASSERT_FALSE(wrong_dim);
  EXPECT_EQ(wrong_dim.error().kind, ErrorKind::invalid_argument);
  EXPECT_NE(wrong_dim.error().message.find("joint SHOULDER"), std::string::npos);
  EXPECT_NE(wrong_dim.error().message.find("is a length, but this is an angle"), std::string::npos);
  EXPECT_NE(wrong_dim.error().message.find("deg, rad"), std::string::npos);
  for (const char* bad : {"", "deg", "nan", "nandeg", "infdeg", "1e400deg", "30", "30 deg", "30degs", "--1deg", "1deg/s"}) {
    EXPECT_FALSE(parse_quantity(bad, Dimension::angle, "j")) << bad;
  }
  EXPECT_FALSE(parse_quantity("90deg", Dimension::angle, "v", 1));  // a velocity needs /s
  EXPECT_FALSE(parse_quantity("90deg/s", Dimension::angle, "a", 2));
}

// The one parser of speeds, overrides and their ranges (item 10 of issue 21): refused in
// the user's words and unit, with the range, never as an internal quantity.
TEST(Quantity, RangesAndPercentagesInTheUsersWords) {
  EXPECT_DOUBLE_EQ(*parse_quantity_in("40mm/s", Dimension::length, "--speed", 1, "mm/s", 1e-4, 0.5), 0.04);
  EXPECT_EQ(parse_quantity_in("1e-300mm/s", Dimension::length, "--speed", 1, "mm/s", 1e-4, 0.5).error().message,
            "--speed: '1e-300mm/s' is too slow; allowed 0.1..500 mm/s");
  EXPECT_EQ(parse_quantity_in("2m/s", Dimension::length, "--speed", 1, "mm/s", 1e-4, 0.5).error().message,
            "--speed: '2m/s' is too fast; allowed 0.1..500 mm/s");
  EXPECT_EQ(check_quantity_in(1e-300, Dimension::length, "speed", 1, 1e-4, 0.5).error().message,
            "speed: 1e-300 m/s is too slow; allowed 0.1..500 mm/s");
  EXPECT_EQ(check_quantity_in(std::nan(""), Dimension::angle, "angular speed", 1, 0.1, 1).error().message.find(
                "is not a number"),
            std::string("angular speed: nan rad/s ").size());
  EXPECT_DOUBLE_EQ(*parse_percent("50%", "--override", 0.001, 1), 0.5);
  EXPECT_DOUBLE_EQ(*parse_percent("+0.1%", "--override", 0.001, 1), 0.001);
  EXPECT_EQ(parse_percent("50", "--override", 0.001, 1).error().message,
            "--override: '50' has no unit; write a percentage like 50%, within 0.1..100 %");
  EXPECT_EQ(parse_percent("1e-300%", "--override", 0.001, 1).error().message,
            "--override: '1e-300%' is too small; allowed 0.1..100 %");
  EXPECT_EQ(parse_percent("101%", "--override", 0.001, 1).error().message,
            "--override: '101%' is too large; allowed 0.1..100 %");
  EXPECT_EQ(parse_percent("1e999%", "--override", 0.001, 1).error().message, "--override: '1e999%' is outside 0.1..100 %");
  for (const char* bad : {"", "%", "nan%", "inf%", "fast", "5 %", "50%%"})
    EXPECT_NE(parse_percent(bad, "--override", 0.001, 1).error().message.find("is not a percentage"), std::string::npos)
        << bad;
  EXPECT_TRUE(check_fraction_in(0.5, "speed_override", 0.001, 1));
  EXPECT_EQ(check_fraction_in(1e-300, "speed_override", 0.001, 1).error().message,
            "speed_override: 1e-300 is too small; allowed 0.001..1 (0.1..100 %)");
}

TEST(Quantity, FormatsForPeople) {
  EXPECT_EQ(format_quantity(Dimension::angle, std::numbers::pi), "180.000 deg");
  EXPECT_EQ(format_quantity(Dimension::length, 0.1205, 1), "120.500 mm/s");
  EXPECT_EQ(format_quantity(Dimension::angle, -1e-12), "0.000 deg");
}

}  // namespace
}  // namespace armctl

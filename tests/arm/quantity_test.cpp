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

TEST(Quantity, FormatsForPeople) {
  EXPECT_EQ(format_quantity(Dimension::angle, std::numbers::pi), "180.000 deg");
  EXPECT_EQ(format_quantity(Dimension::length, 0.1205, 1), "120.500 mm/s");
  EXPECT_EQ(format_quantity(Dimension::angle, -1e-12), "0.000 deg");
}

}  // namespace
}  // namespace armctl

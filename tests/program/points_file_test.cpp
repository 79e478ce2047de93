// Points files (program/points_file.hpp): every form, every error with its place, the
// writer's round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include <unistd.h>

#include "program/points_file.hpp"

namespace armctl::program {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

std::string error_of(std::string_view text) {
  auto r = parse_points_file(text, "p.points");
  EXPECT_FALSE(r.ok()) << text;
  return r ? std::string() : r.error().message;
}

TEST(PointsFile, ReadsJointsAndPoses) {
  auto f = parse_points_file(
      "# comment\n"
      "home   joints=0deg,30deg,-45deg,120mm   # trailing comment\n"
      "\n"
      "  pick x=200mm y=-10mm z=0.04m pitch=90deg elbow=up\n",
      "p.points");
  ASSERT_TRUE(f) << f.error().message;
  ASSERT_EQ(f->points.size(), 2u);
  const Point& home = f->points[0];
  EXPECT_EQ(home.name, "home");
  EXPECT_EQ(home.line, 2u);
  ASSERT_EQ(home.joints.size(), 4u);
  EXPECT_NEAR(home.joints[1].value, 30 * kDeg, 1e-12);
  EXPECT_EQ(home.joints[3].dimension, Dimension::length);
  EXPECT_NEAR(home.joints[3].value, 0.12, 1e-12);
  const Point& pick = *f->find("pick");
  EXPECT_FALSE(pick.is_joints());
  EXPECT_NEAR(pick.position.x(), 0.2, 1e-12);
  EXPECT_NEAR(pick.position.y(), -0.01, 1e-12);
  EXPECT_NEAR(pick.position.z(), 0.04, 1e-12);
  EXPECT_NEAR(*pick.pitch, 90 * kDeg, 1e-12);
  EXPECT_FALSE(pick.roll.has_value());
  EXPECT_EQ(pick.elbow, motion::Elbow::up);
  EXPECT_EQ(f->find("Pick"), nullptr);  // names are case-sensitive
}

TEST(PointsFile, AnEmptyFileHasNoPoints) {
  auto f = parse_points_file("# nothing yet\n\n", "p.points");
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->points.empty());
}

TEST(PointsFile, EveryErrorNamesTheFileLineAndColumn) {
  EXPECT_EQ(error_of("x=1mm y=2mm z=3mm\n"),
            "p.points:1:1: found 'x=1mm', expected a point's name first (e.g. 'pick x=200mm y=0mm z=40mm')");
  EXPECT_EQ(error_of("home joints=0deg\n2go x=1mm y=1mm z=1mm\n"),
            "p.points:2:1: found '2go', expected a point name: a name starts with a letter or '_'");
  EXPECT_EQ(error_of("lin x=1mm y=1mm z=1mm\n"),
            "p.points:1:1: found 'lin', expected a point name: 'lin' is a word of the program language");
  EXPECT_EQ(error_of("a joints=0deg\na joints=1deg\n"), "p.points:2:1: found 'a', expected each point name once");
  EXPECT_EQ(error_of("home\n"),
            "p.points:1:5: found '', expected the point's position after its name: joints=..., or x, y, z with "
            "roll, pitch, yaw, elbow");
  EXPECT_EQ(error_of("home speed=50%\n"),
            "p.points:1:6: found 'speed', expected a point's key=value: joints=..., or x, y, z with roll, pitch, yaw, elbow");
  // The values are read as a path file's: the column is the value's in this file.
  const std::string unit = error_of("home  x=200 y=0mm z=0mm\n");
  EXPECT_EQ(unit.rfind("p.points:1:9: ", 0), 0u) << unit;
  const std::string both = error_of("long_name joints=0deg x=1mm\n");
  EXPECT_NE(both.find("a point to joints"), std::string::npos) << both;
  EXPECT_EQ(both.rfind("p.points:1:", 0), 0u) << both;
}

TEST(PointsFile, FormatsAndReadsBack) {
  PointsFile f;
  Point a;
  a.name = "home";
  a.joints = {{0.1, Dimension::angle}, {-1.2345678901234, Dimension::angle}, {0.123456, Dimension::length}};
  Point b;
  b.name = "pick_2";
  b.position = {0.2, -0.0333333333333, 0.04};
  b.pitch = std::numbers::pi / 2;
  b.yaw = -0.3;
  b.elbow = motion::Elbow::down;
  f.points = {a, b};
  auto again = parse_points_file(format_points_file(f), "again");
  ASSERT_TRUE(again) << again.error().message << "\n" << format_points_file(f);
  ASSERT_EQ(again->points.size(), 2u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(again->points[0].joints[i].value, a.joints[i].value, 1e-15);
  EXPECT_EQ(again->points[0].joints[2].dimension, Dimension::length);
  EXPECT_NEAR((again->points[1].position - b.position).norm(), 0, 1e-15);
  EXPECT_NEAR(*again->points[1].pitch, *b.pitch, 1e-15);
  EXPECT_EQ(again->points[1].elbow, b.elbow);
  EXPECT_FALSE(again->points[1].roll.has_value());
}

TEST(PointsFile, WritesAtomicallyAndRefusesBadNames) {
  const auto path = std::filesystem::temp_directory_path() / ("armctl-points-" + std::to_string(::getpid()) + ".points");
  PointsFile f;
  Point p;
  p.name = "p1";
  p.joints = {{0.5, Dimension::angle}};
  f.points = {p};
  ASSERT_TRUE(write_points_file(path, f));
  auto back = read_points_file(path);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->points.size(), 1u);
  f.points[0].name = "while";
  auto bad = write_points_file(path, f);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "point 'while': 'while' is a word of the program language");
  EXPECT_EQ(read_points_file(path)->points[0].name, "p1");  // the old file is kept
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace armctl::program

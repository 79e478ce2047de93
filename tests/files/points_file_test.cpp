// Points files (files/points_file.hpp): every form, every error with its place, the
// writer's round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>

#include "core/source_place.hpp"
#include "files/path_file.hpp"
#include "files/points_file.hpp"

namespace armctl::files {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// Every such error carries its place (SourcePlace) and its message is that place's rendering.
void expect_placed(const Error& e) {
  const SourcePlace* at = source_place(e);
  ASSERT_NE(at, nullptr) << e.message;
  EXPECT_EQ(source_error(e.kind, *at).message, e.message);
}

std::string error_of(std::string_view text) {
  auto r = parse_points_file(text, "p.points");
  EXPECT_FALSE(r.ok()) << text;
  if (!r) expect_placed(r.error());
  return r ? std::string() : r.error().message;
}

PointsFile read_back(std::string_view text) {
  auto r = parse_points_file(text.substr(text.starts_with("\xEF\xBB\xBF") ? 3 : 0), "p.points");
  EXPECT_TRUE(r.ok()) << (r ? "" : r.error().message);
  return r ? std::move(r).value() : PointsFile{};
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

// What a person wrote stays: a byte-order mark, comments, blank lines, CRLF line ends, the
// order, odd spacing and number forms of untouched points, a changed point's alignment and
// trailing comment; a removed point's line goes, a new one comes last.
TEST(PointsFile, UpdatingKeepsEveryLineAPersonWrote) {
  const std::string text =
      "\xEF\xBB\xBF# my cell\r\n"
      "\r\n"
      "home   joints=0deg,20deg   # safe\r\n"
      "  pick x=200mm y=0mm z=0.04m\r\n"
      "# old\r\n"
      "gone joints=1deg\r\n"
      "place  x=1e2mm  y=150mm z=40mm";  // no line end at the end
  auto f = read_back(text);
  EXPECT_EQ(update_points_text(text, f, "p.points").value(), text);  // nothing changed: byte for byte

  const PointsFile taught = parse_points_file("home joints=10deg,20deg\nnew joints=5deg\n").value();
  f.points[0].joints = taught.points[0].joints;
  std::erase_if(f.points, [](const Point& p) { return p.name == "gone"; });
  f.points.push_back(taught.points[1]);
  const std::string home = format_point_fields(f.points[0]);
  ASSERT_EQ(home.rfind("joints=10", 0), 0u) << home;
  EXPECT_EQ(update_points_text(text, f, "p.points").value(),
            "\xEF\xBB\xBF# my cell\r\n"
            "\r\n"
            "home   " + home + "   # safe\r\n"
            "  pick x=200mm y=0mm z=0.04m\r\n"
            "# old\r\n"
            "place  x=1e2mm  y=150mm z=40mm\r\n"
            "new   joints=5deg\r\n");
}

TEST(PointsFile, UpdatingRefusesTextThatDoesNotParse) {
  auto r = update_points_text("# mine\nhome joints=banana\n", PointsFile{}, "p.points");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message.rfind("p.points:2:", 0), 0u) << r.error().message;
  EXPECT_NE(r.error().message.find("the file is left as it is"), std::string::npos) << r.error().message;
}

TEST(PointsFile, WritingAnExistingFileKeepsItsComments) {
  const auto path = std::filesystem::temp_directory_path() / ("armctl-points-kept-" + std::to_string(::getpid()) + ".points");
  std::ofstream(path, std::ios::binary) << "# my cell\nhome joints=0deg  # safe\n";
  auto f = read_points_file(path).value();
  f.points.push_back(parse_points_file("p1 joints=1deg\n").value().points[0]);
  ASSERT_TRUE(write_points_file(path, f));
  std::ifstream in(path, std::ios::binary);
  const std::string back((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(back, "# my cell\nhome joints=0deg  # safe\np1   joints=1deg\n");
  std::filesystem::remove(path);
}

// Editors on other systems start a file with EF BB BF: it is read as nothing, and the
// columns of errors are the characters' (the mark is not one).
TEST(PointsFile, AByteOrderMarkIsNotPartOfAPointsOrPathFile) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto points = dir / ("armctl-bom-" + std::to_string(::getpid()) + ".points");
  std::ofstream(points, std::ios::binary) << "\xEF\xBB\xBFhome joints=10deg\n";
  auto read = read_points_file(points);
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->points.size(), 1u);
  EXPECT_EQ(read->points[0].name, "home");
  std::ofstream(points, std::ios::binary) << "\xEF\xBB\xBFhome  x=200 y=0mm z=0mm\n";
  const std::string error = read_points_file(points).error().message;
  EXPECT_EQ(error, points.string() + error_of("home  x=200 y=0mm z=0mm\n").substr(std::string("p.points").size()));
  EXPECT_NE(error.find(":1:9: "), std::string::npos) << error;
  std::filesystem::remove(points);

  const auto path = dir / ("armctl-bom-" + std::to_string(::getpid()) + ".path");
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBFptp joints=10deg\n";
  auto moves = files::read_path_file(path);
  ASSERT_TRUE(moves) << moves.error().message;
  EXPECT_EQ(moves->moves.size(), 1u);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace armctl::files

// Path files: every form of move, units, comments, the canonical text's round trip, and
// every error with its file, line and column, what was found and what is expected.
#include "files/path_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <gmock/gmock.h>

#include "core/source_place.hpp"
#include <gtest/gtest.h>

namespace armctl::files {
namespace {

using motion::Elbow;

using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180; }

PathFile parsed(const std::string& text) {
  auto f = parse_path_file(text, "t.path");
  if (!f) throw std::runtime_error(f.error().message);
  return std::move(f).value();
}

std::string refused(const std::string& text) {
  auto f = parse_path_file(text, "t.path");
  EXPECT_FALSE(f.ok()) << text;
  if (f) return "";
  EXPECT_EQ(f.error().kind, ErrorKind::invalid_config);
  // An error at a line carries its place (SourcePlace), rendered as its message.
  if (const SourcePlace* at = source_place(f.error())) {
    EXPECT_EQ(at->file, "t.path");
    EXPECT_EQ(source_error(f.error().kind, *at).message, f.error().message);
  } else {
    EXPECT_EQ(f.error().message.rfind("t.path: ", 0), 0u) << "a line's error without its place: " << f.error().message;
  }
  return f.error().message;
}

TEST(PathFile, EveryFormOfMove) {
  const PathFile f = parsed(
      "# pick and place\n"
      "\n"
      "ptp  joints=0deg,30deg,-45deg,0.5rad,0deg   speed=50%\n"
      "ptp  x=200mm y=0mm z=150mm pitch=90deg elbow=up  speed=30%   # above the part\n"
      "lin  x=200mm y=100mm z=150mm speed=50mm/s zone=5mm\n"
      "circ via=250mm,150mm,150mm x=300mm y=100mm z=150mm speed=40mm/s angular_speed=30deg/s\n"
      "LIN\tx=0.3m y=-0.1m z=0.1m roll=180deg pitch=0deg yaw=-90deg\r\n"
      "ptp joints=120mm,10deg\n");
  ASSERT_EQ(f.moves.size(), 6u);
  const PathMove& a = f.moves[0];
  EXPECT_EQ(a.kind, MoveKind::ptp);
  EXPECT_EQ(a.line, 3u);
  ASSERT_EQ(a.joints.size(), 5u);
  EXPECT_NEAR(a.joints[1].value, deg(30), 1e-15);
  EXPECT_EQ(a.joints[3], (JointValue{0.5, Dimension::angle}));
  EXPECT_DOUBLE_EQ(*a.speed_fraction, 0.5);
  EXPECT_FALSE(a.speed);
  const PathMove& b = f.moves[1];
  EXPECT_TRUE(b.joints.empty());
  EXPECT_EQ(b.line, 4u);
  EXPECT_NEAR((b.position - Eigen::Vector3d(0.2, 0, 0.15)).norm(), 0, 1e-15);
  EXPECT_NEAR(*b.pitch, deg(90), 1e-15);
  EXPECT_FALSE(b.roll);
  EXPECT_FALSE(b.yaw);
  EXPECT_EQ(b.elbow, Elbow::up);
  EXPECT_DOUBLE_EQ(*b.speed_fraction, 0.3);
  const PathMove& c = f.moves[2];
  EXPECT_EQ(c.kind, MoveKind::lin);
  EXPECT_DOUBLE_EQ(*c.speed, 0.05);
  EXPECT_DOUBLE_EQ(c.zone, 0.005);
  EXPECT_FALSE(c.angular_speed);
  const PathMove& d = f.moves[3];
  EXPECT_EQ(d.kind, MoveKind::circ);
  EXPECT_NEAR((d.via - Eigen::Vector3d(0.25, 0.15, 0.15)).norm(), 0, 1e-15);
  EXPECT_NEAR(*d.angular_speed, deg(30), 1e-15);
  EXPECT_EQ(d.zone, 0);
  const PathMove& e = f.moves[4];
  EXPECT_EQ(e.kind, MoveKind::lin);
  EXPECT_EQ(e.line, 7u);
  EXPECT_NEAR(*e.roll, kPi, 1e-15);
  EXPECT_NEAR(*e.yaw, -kPi / 2, 1e-15);
  EXPECT_EQ(f.moves[5].joints[0], (JointValue{0.12, Dimension::length}));
  EXPECT_FALSE(f.moves[5].speed_fraction);  // left to the default
}

TEST(PathFile, CanonicalTextParsesBackToTheSameMoves) {
  const PathFile f = parsed(
      "ptp joints=0deg,30deg,-45deg,12.5mm speed=33.3%\n"
      "ptp x=200mm y=0mm z=150mm yaw=10deg elbow=left\n"
      "lin x=200.1mm y=100mm z=150mm speed=50mm/s zone=5mm angular_speed=1rad/s\n"
      "circ via=250mm,150mm,150mm x=300mm y=100mm z=150mm roll=-3deg\n");
  const PathFile again = parsed(format_path_file(f));
  ASSERT_EQ(again.moves.size(), f.moves.size());
  for (std::size_t i = 0; i < f.moves.size(); ++i) {
    PathMove a = f.moves[i], b = again.moves[i];
    ASSERT_EQ(a.speed_fraction.has_value(), b.speed_fraction.has_value());
    if (a.speed_fraction) {
      EXPECT_NEAR(*a.speed_fraction, *b.speed_fraction, 1e-15);
    }
    a.line = b.line = 0;
    a.speed_fraction = b.speed_fraction = std::nullopt;
    EXPECT_EQ(a, b) << "move " << i + 1 << "\n" << format_path_file(f);
  }
}

TEST(PathFile, ErrorsNameFileLineColumnFoundAndExpected) {
  EXPECT_EQ(refused("jog x=1mm\n"), "t.path:1:1: found 'jog', expected a move: ptp, lin or circ");
  EXPECT_EQ(refused("\n  lin x=1mm y=2mm z=3mm speed\n"),
            "t.path:2:25: found 'speed', expected key=value; a lin takes x, y, z, roll, pitch, yaw, speed, "
            "angular_speed, zone");
  EXPECT_EQ(refused("lin x=1mm y=2mm z=3mm joints=1deg\n"),
            "t.path:1:23: found 'joints', expected a key a lin takes: x, y, z, roll, pitch, yaw, speed, angular_speed, "
            "zone");
  EXPECT_EQ(refused("ptp x=1mm y=2mm z=3mm zone=1mm\n"),
            "t.path:1:23: found 'zone', expected a key a ptp takes: joints, or x, y, z with roll, pitch, yaw, elbow; "
            "speed (N%)");
  EXPECT_EQ(refused("lin x=1mm y=2mm z=3mm x=4mm\n"), "t.path:1:23: found 'x', expected each key once per line");
  EXPECT_EQ(refused("lin x=1mm y= z=3mm\n"), "t.path:1:13: found '', expected a value after 'y='");
  EXPECT_EQ(refused("lin x=12 y=0mm z=0mm\n"),
            "t.path:1:7: x: '12' has no unit; write a number with one of the units mm, m");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0deg\n"),
            "t.path:1:19: z: '0deg' is an angle, but this is a length; write a number with one of the units mm, m");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm speed=20%\n"),
            "t.path:1:29: found '20%', expected the tool's speed for a lin (e.g. 50mm/s); a percent is for ptp");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm speed=20mm\n"),
            "t.path:1:29: speed: '20mm' has the unknown unit 'mm'; write a number with one of the units mm/s, m/s");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm speed=0mm/s\n"),
            "t.path:1:29: found '0mm/s', expected a speed within 0.1..500 mm/s (e.g. 50mm/s)");
  // 1e-300 mm/s was accepted (a move of many lifetimes, "would take -9223372036.9 s").
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm speed=1e-300mm/s\n"),
            "t.path:1:29: found '1e-300mm/s', expected a speed within 0.1..500 mm/s (e.g. 50mm/s)");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm speed=1e300mm/s\n"),
            "t.path:1:29: found '1e300mm/s', expected a speed within 0.1..500 mm/s (e.g. 50mm/s)");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm angular_speed=-1deg/s\n"),
            "t.path:1:37: found '-1deg/s', expected an angular speed within 0.1..720 deg/s (e.g. 30deg/s)");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm angular_speed=1e-300rad/s\n"),
            "t.path:1:37: found '1e-300rad/s', expected an angular speed within 0.1..720 deg/s (e.g. 30deg/s)");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm zone=-1mm\n"),
            "t.path:1:28: found '-1mm', expected a zone >= 0 (e.g. 5mm; 0 stops exactly at the target)");
  EXPECT_EQ(refused("ptp joints=1deg speed=0%\n"),
            "t.path:1:23: found '0%', expected a ptp speed in percent of the joints' velocity limits, 0.1..100 % "
            "(e.g. 50%)");
  EXPECT_THAT(refused("ptp joints=1deg speed=1e-300%\n"), HasSubstr("found '1e-300%', expected a ptp speed"));
  EXPECT_THAT(refused("ptp joints=1deg speed=50\n"), HasSubstr("found '50', expected a ptp speed"));
  EXPECT_THAT(refused("ptp joints=1deg speed=101%\n"), HasSubstr("found '101%'"));
  EXPECT_THAT(refused("ptp joints=1deg speed=nan%\n"), HasSubstr("found 'nan%'"));
  EXPECT_EQ(refused("lin x=1mm y=0mm\n"), "t.path:1:16: found '', expected z=: a lin needs the tool's position x, y and z");
  EXPECT_EQ(refused("circ x=1mm y=0mm z=0mm\n"),
            "t.path:1:23: found '', expected via=x,y,z: a circ needs a point on the arc between start and target");
  EXPECT_EQ(refused("circ via=1mm,2mm x=1mm y=0mm z=0mm\n"),
            "t.path:1:10: found '1mm,2mm', expected three lengths x,y,z for via (e.g. via=250mm,150mm,150mm)");
  EXPECT_EQ(refused("circ via=1mm,2m,3 x=1mm y=0mm z=0mm\n"),
            "t.path:1:17: via: '3' has no unit; write a number with one of the units mm, m");
  EXPECT_EQ(refused("ptp joints=1deg,,2deg\n"),
            "t.path:1:17: found '', expected a joint value between the commas (e.g. 30deg or 120mm)");
  EXPECT_EQ(refused("ptp joints=1deg,2kg\n"),
            "t.path:1:17: found '2kg', expected a joint value: a number with deg or rad (revolute), mm or m (prismatic)");
  EXPECT_THAT(refused("ptp joints=1deg,1deg,1deg,1deg,1deg,1deg,1deg,1deg,1deg\n"),
              HasSubstr("expected at most 8 joint values"));
  EXPECT_EQ(refused("ptp joints=1deg x=1mm\n"),
            "t.path:1:1: found 'ptp', expected a ptp to joints (joints=...) or to a pose (x, y, z ...), not both");
  EXPECT_EQ(refused("ptp speed=50%\n"), "t.path:1:14: found '', expected the ptp's target: joints=... or x=, y=, z=");
  EXPECT_EQ(refused("ptp x=1mm y=0mm z=0mm elbow=sideways\n"),
            "t.path:1:29: found 'sideways', expected elbow up or down (xArm), left or right (SCARA)");
  EXPECT_EQ(refused("# only a comment\n\n"), "t.path: the file has no moves; expected lines of ptp, lin or circ moves");
  EXPECT_EQ(refused("lin x=1mm y=0mm z=0mm\nlin =1mm\n"),
            "t.path:2:5: found '=1mm', expected key=value; a lin takes x, y, z, roll, pitch, yaw, speed, angular_speed, "
            "zone");
  EXPECT_THAT(refused("lin x=1mm\x01 y=0mm z=0mm\n"), HasSubstr("'1mm\\x01'"));  // control bytes escaped
}

TEST(PathFile, ReadsAFileAndRefusesWhatIsNotOne) {
  const auto dir = std::filesystem::path(ARMCTL_BINARY_DIR) / "path_file_test";
  std::filesystem::create_directories(dir);
  const auto file = dir / "square.path";
  std::ofstream(file) << "lin x=100mm y=0mm z=50mm zone=2mm\nlin x=100mm y=100mm z=50mm\n";
  auto f = read_path_file(file);
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_EQ(f->moves.size(), 2u);
  std::ofstream(dir / "bad.path") << "lin x=100mm\n";
  auto bad = read_path_file(dir / "bad.path");
  ASSERT_FALSE(bad.ok());
  EXPECT_THAT(bad.error().message, HasSubstr((dir / "bad.path").string() + ":1:12: found ''"));
  auto missing = read_path_file(dir / "missing.path");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().kind, ErrorKind::io);
  EXPECT_THAT(missing.error().message, HasSubstr("no such file"));
  auto directory = read_path_file(dir);
  ASSERT_FALSE(directory.ok());
  EXPECT_THAT(directory.error().message, HasSubstr("is not a regular file"));
  EXPECT_THAT(parse_path_file(std::string((1 << 20) + 1, '#'), "big").error().message,
              HasSubstr("larger than a path file may be (1 MiB)"));
}

}  // namespace
}  // namespace armctl::files

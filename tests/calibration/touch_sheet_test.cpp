// The verify sheet and the verify step: the marks lie where the sheet's layout puts them and
// the arm can reach each; verify reports the residual per point; from the mis-assembled arm's
// points, the fit written to the arm file makes verify pass on the sheet where it failed.
#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>

#include <unistd.h>

#include <fmt/core.h>

#include "calibration/arm_file_writer.hpp"
#include "calibration/kinematic_fit.hpp"
#include "calibration/touch_sheet.hpp"
#include "synthetic_arm.hpp"

namespace armctl::calibration {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kMm = 1e-3;
namespace fs = std::filesystem;

// The tool point at `p`, its approach (the tool frame's x axis, on both arms) facing away
// from the base and tilted `pitch` below the horizontal.
motion::Pose tilted(const Eigen::Vector3d& p, double pitch) {
  const Eigen::Quaterniond o(Eigen::AngleAxisd(std::atan2(p.y(), p.x()), Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
  return motion::Pose{p, o};
}

// The first IK solution that puts the tool point on `p`, pointing straight down or, where
// the arm cannot, tilted up to 60 deg from straight down (a pointed tool touches at an angle).
Result<motion::JointVector> touch(const arm::ArmModel& m, const Eigen::Vector3d& p) {
  Error last{ErrorKind::invalid_argument, "no pitch tried"};
  for (double pitch_deg = 90; pitch_deg >= 30; pitch_deg -= 5) {
    motion::Pose link = tilted(p, pitch_deg * kDeg);
    link.position -= link.orientation * m.tool.position;  // the tool link's pose for the tool point
    auto ik = m.kinematics->inverse(motion::IkRequest{link, m.family == "xarm"},
                                    motion::JointVector::Zero(m.chain_joints()));
    if (ik) return ik->front().joints;
    last = ik.error();
  }
  return last;
}

TEST(Sheet, TheMarksAreTheLayoutsOnBothArms) {
  for (const char* arm : {"xarm", "scara"}) {
    SCOPED_TRACE(arm);
    const arm::ArmModel m = arm::testing::shipped(arm);
    const SheetPlacement place = default_placement(m);
    auto marks = sheet_points(m, place);
    ASSERT_TRUE(marks) << marks.error().message;
    ASSERT_EQ(marks->size(), std::size(kSheetMarks));
    for (std::size_t i = 0; i < marks->size(); ++i) {
      const Eigen::Vector3d& p = (*marks)[i].position;
      EXPECT_EQ((*marks)[i].name, kSheetMarks[i].name);
      EXPECT_NEAR(p.z(), place.height, 1e-12);
      // On the sheet: x from the near edge to the far one, y within its width, centred.
      EXPECT_GE(p.x(), place.distance);
      EXPECT_LE(p.x(), place.distance + kSheetLength);
      EXPECT_LE(std::abs(p.y()), kSheetWidth / 2);
      // Distances between marks are the sheet's: the mapping is a rigid placement.
      for (std::size_t k = 0; k < i; ++k) {
        const double on_sheet = std::hypot(kSheetMarks[i].u - kSheetMarks[k].u, kSheetMarks[i].v - kSheetMarks[k].v);
        EXPECT_NEAR((p - (*marks)[k].position).norm(), on_sheet, 1e-12);
      }
      // The arm reaches every mark with its tool pointing down, or tilted.
      auto q = touch(m, p);
      EXPECT_TRUE(q) << (*marks)[i].name << ": " << q.error().message;
    }
  }
}

TEST(Sheet, BadPlacementsAndPointsAreRefused) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  EXPECT_FALSE(sheet_points(m, {0.0, 0.0}));          // on the base
  EXPECT_FALSE(sheet_points(m, {std::nan(""), 0.0}));
  auto far = sheet_points(m, {0.3, 0.0});              // beyond the xArm's reach
  ASSERT_FALSE(far);
  EXPECT_NE(far.error().message.find("sheet mark"), std::string::npos) << far.error().message;
  EXPECT_TRUE(user_point(m, "cup", {0.15, 0.05, 0.02}));
  EXPECT_FALSE(user_point(m, "", {0.15, 0.05, 0.02}));
  EXPECT_FALSE(user_point(m, "moon", {4e8, 0, 0}));
}

// The mis-assembled arm's joint readings at the sheet's marks: the true arm's IK, less its
// zero errors.
std::vector<TouchedPoint> touch_sheet(const arm::ArmModel& nominal, const testing::Truth& truth) {
  const arm::ArmModel real = testing::true_arm(nominal.name, truth);
  std::vector<TouchedPoint> out;
  const std::vector<NamedPoint> marks = sheet_points(nominal, default_placement(nominal)).value();
  for (const NamedPoint& mark : marks) {
    auto ik = touch(real, mark.position);
    EXPECT_TRUE(ik) << ik.error().message;
    if (!ik) continue;
    TouchedPoint p{mark.name, {}, mark.position};
    const motion::JointVector& q = *ik;
    for (int i = 0; i < q.size(); ++i) {
      auto e = truth.zero_error.find(nominal.joints[std::size_t(i)].name);
      p.joints.push_back(q[i] - (e == truth.zero_error.end() ? 0.0 : e->second));
    }
    out.push_back(p);
  }
  return out;
}

TEST(Verify, TheFitWrittenToTheArmFileMakesTheSheetTrue) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("armctl-calfit-verify-{}", ::getpid());
  fs::create_directories(dir);
  for (const char* f : {"xarm.arm.json", "xarm.urdf", "scara.arm.json", "scara.urdf"})
    fs::copy_file(arm::testing::config_path(f), dir / f, fs::copy_options::overwrite_existing);
  testing::Truth xarm;
  xarm.zero_error = {{"servo6", 2.0 * kDeg}, {"servo5", -3.1 * kDeg}, {"servo4", 1.7 * kDeg}, {"servo3", -2.5 * kDeg}};
  xarm.length = {{"servo5", 34.0 * kMm}, {"servo4", 95.2 * kMm}, {"servo3", 100.1 * kMm}, {"tool_point", 46.3 * kMm}};
  testing::Truth scara;
  scara.zero_error = {{"Z", 1.5 * kMm}, {"SHOULDER", 2.2 * kDeg}, {"UAE", -1.8 * kDeg},
                      {"UAJ", 3.0 * kDeg}, {"SKE", -2.4 * kDeg}, {"SKF", 1.1 * kDeg}};
  scara.length = {{"UAE", 258.4 * kMm}, {"UAJ", 251.9 * kMm}, {"tool_point", 179.2 * kMm}};
  for (const auto& [arm, truth] : {std::pair{"xarm", xarm}, std::pair{"scara", scara}}) {
    SCOPED_TRACE(arm);
    const arm::ArmModel nominal = arm::load_arm_model(dir / fmt::format("{}.arm.json", arm)).value();
    const auto sheet = touch_sheet(nominal, truth);
    ASSERT_EQ(sheet.size(), std::size(kSheetMarks));
    auto before = verify_points(nominal, sheet);
    ASSERT_TRUE(before) << before.error().message;
    std::cout << arm << " sheet before: " << to_text(*before) << "\n";
    EXPECT_GT(before->max, 3 * kMm);
    auto fit = fit_kinematics(nominal, testing::touched_points(nominal, truth, {.count = 20, .seed = 4}));
    ASSERT_TRUE(fit) << fit.error().message;
    // Before anything is written, the sheet on the fitted arm.
    auto preview = verify_fit(nominal, *fit, sheet);
    ASSERT_TRUE(preview) << preview.error().message;
    EXPECT_LT(preview->max, 0.5 * kMm);
    auto written = write_calibration(nominal, changes_from_fit(nominal, *fit));
    ASSERT_TRUE(written) << written.error().message;
    const arm::ArmModel calibrated = arm::load_arm_model(nominal.file).value();
    // The same poses read through the calibrated arm file: the device positions stay, the
    // readings change with the new zeros.
    std::vector<TouchedPoint> read_again = sheet;
    for (TouchedPoint& p : read_again) {
      std::vector<double> all = p.joints;
      all.resize(nominal.joints.size(), 0.0);  // the gripper, wherever it is
      const arm::Protocol protocol = nominal.supports(arm::Protocol::joint_bus) ? arm::Protocol::joint_bus
                                                                                : arm::Protocol::robot_commands;
      std::vector<double> q = calibrated.from_device(protocol, nominal.to_device(protocol, all));
      q.resize(p.joints.size());
      p.joints = q;
    }
    auto after = verify_points(calibrated, read_again);
    ASSERT_TRUE(after) << after.error().message;
    std::cout << arm << " sheet after: " << to_text(*after) << "\n";
    EXPECT_LT(after->max, 0.5 * kMm);
  }
  fs::remove_all(dir);
}

TEST(Verify, WrongReadingsAreRefusedNamingThePoint) {
  const arm::ArmModel m = arm::testing::shipped("scara");
  std::vector<TouchedPoint> points{{"A", std::vector<double>(6, 0.0), {0.4, 0, 0.2}},
                                   {"B", std::vector<double>(6, 0.0), {0.4, 0, 0.2}}};
  points[1].joints[1] = 200 * kDeg;  // beyond SHOULDER's 150 deg
  auto r = verify_points(m, points);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("('B')"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("SHOULDER"), std::string::npos) << r.error().message;
  EXPECT_FALSE(verify_points(m, {}));
}

}  // namespace
}  // namespace armctl::calibration

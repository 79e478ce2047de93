// The kinematic fit on synthetic data of both arms: the true arm's zeros off by degrees and
// lengths by millimetres, points touched with noise up to 0.3 mm; the fit must recover the
// lengths within 0.5 mm and the zeros within one device unit (computed from the arm file's
// maps), and refuse point sets that cannot tell a parameter apart, naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "calibration/kinematic_fit.hpp"
#include "synthetic_arm.hpp"

namespace armctl::calibration {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kMm = 1e-3;

// One device unit of the joint, in its SI unit: an xArm servo unit (240 deg / 1000), a
// joint-bus click of the SCARA (a turn / 10115.702).
double device_unit(const arm::ArmModel& m, int joint, arm::Protocol p) {
  return 1.0 / std::abs(m.joints[std::size_t(joint)].map(p)->device_per_unit());
}

bool names_any(const std::vector<Parameter>& ps, const std::string& text) {
  return std::any_of(ps.begin(), ps.end(), [&](const Parameter& p) { return p.name.find(text) != std::string::npos; });
}

testing::Truth xarm_truth() {
  testing::Truth t;
  t.zero_error = {{"servo6", 2.0 * kDeg}, {"servo5", -3.1 * kDeg}, {"servo4", 1.7 * kDeg}, {"servo3", -2.5 * kDeg}};
  t.length = {{"servo5", 34.0 * kMm}, {"servo4", 95.2 * kMm}, {"servo3", 100.1 * kMm}, {"tool_point", 46.3 * kMm}};
  return t;
}

testing::Truth scara_truth() {
  testing::Truth t;
  t.zero_error = {{"Z", 1.5 * kMm},      {"SHOULDER", 2.2 * kDeg}, {"UAE", -1.8 * kDeg},
                  {"UAJ", 3.0 * kDeg},   {"SKE", -2.4 * kDeg},     {"SKF", 1.1 * kDeg}};
  t.length = {{"UAE", 258.4 * kMm}, {"UAJ", 251.9 * kMm}, {"tool_point", 179.2 * kMm}};
  return t;
}

void print(const std::string& what, const FitResult& r) {
  std::cout << what << ": before rms " << r.before.rms / kMm << " mm max " << r.before.max / kMm << " mm; after rms "
            << r.after.rms / kMm << " mm max " << r.after.max / kMm << " mm; condition " << r.condition << ", "
            << r.iterations << " iterations\n";
}

// Every fitted parameter against the truth: lengths within 0.5 mm, revolute zeros within one
// device unit, a prismatic zero within 0.5 mm (a SCARA Z click is 0.01 mm, far below the
// points' noise: docs/calibration.md).
void expect_recovered(const arm::ArmModel& m, const testing::Truth& truth, const FitResult& r, arm::Protocol p) {
  for (const ParameterEstimate& e : r.estimates) {
    if (e.parameter.kind == ParameterKind::length) {
      auto it = truth.length.find(e.parameter.origin);
      const double nominal = e.length - e.correction;
      double want = it == truth.length.end() ? nominal : it->second;
      // A slide's zero error is a change of the length of its origin (along the slide): the
      // SCARA's Z zero shows in the column's height, which the fit adjusts instead.
      auto slide = m.find_joint(e.parameter.origin);
      if (slide && m.joints[std::size_t(*slide)].dimension == Dimension::length && truth.zero_error.count(e.parameter.origin))
        want += truth.zero_error.at(e.parameter.origin);
      EXPECT_NEAR(e.length, want, 0.5 * kMm) << e.parameter.name;
      std::cout << "  " << e.parameter.name << ": " << e.length / kMm << " mm, true " << want / kMm << " mm, off "
                << (e.length - want) / kMm << " mm (+- " << e.uncertainty / kMm << ")\n";
    } else {
      const arm::JointModel& j = m.joints[std::size_t(e.parameter.joint)];
      auto it = truth.zero_error.find(j.name);
      const double want = it == truth.zero_error.end() ? 0.0 : it->second;
      const double tolerance = j.dimension == Dimension::angle ? device_unit(m, e.parameter.joint, p) : 0.5 * kMm;
      EXPECT_NEAR(e.correction, want, tolerance) << e.parameter.name;
      std::cout << "  " << e.parameter.name << ": off " << (e.correction - want) / tolerance
                << " of the tolerance " << to_display(j.dimension, tolerance) << display_unit(j.dimension) << "\n";
    }
  }
}

TEST(FittableParameters, TheXarmLeavesOutWhatPointsCannotSee) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  auto choice = fittable_parameters(m);
  ASSERT_TRUE(choice) << choice.error().message;
  std::vector<std::string> fitted, left;
  for (const Parameter& p : choice->fitted) fitted.push_back(p.name);
  for (const auto& l : choice->left_out) left.push_back(l.parameter.name);
  EXPECT_EQ(fitted, (std::vector<std::string>{"zero of servo6", "zero of servo5", "zero of servo4", "zero of servo3",
                                              "length of tool_point's origin", "length of servo3's origin",
                                              "length of servo4's origin", "length of servo5's origin"}));
  // The roll's axis passes through the tool point; the roll joint's origin and the tool
  // point's lie along one axis, as do the base's and the shoulder's.
  EXPECT_EQ(left, (std::vector<std::string>{"zero of servo2", "length of servo2's origin", "length of servo6's origin"}));
  ASSERT_EQ(choice->left_out.size(), 3u);
  EXPECT_TRUE(choice->left_out[0].same_as.empty());
  EXPECT_TRUE(names_any(choice->left_out[1].same_as, "tool_point")) << choice->left_out[1].why;
  EXPECT_TRUE(names_any(choice->left_out[2].same_as, "servo5's origin")) << choice->left_out[2].why;
}

TEST(FittableParameters, TheScaraFitsTheBaseHeightNotTheZZero) {
  const arm::ArmModel m = arm::testing::shipped("scara");
  auto choice = fittable_parameters(m);
  ASSERT_TRUE(choice) << choice.error().message;
  ASSERT_EQ(choice->left_out.size(), 1u);
  EXPECT_EQ(choice->left_out[0].parameter.name, "zero of Z");
  ASSERT_EQ(choice->left_out[0].same_as.size(), 1u);
  EXPECT_EQ(choice->left_out[0].same_as[0].name, "length of Z's origin");
  // Five zeros; the tool, forearm, upper arm lengths and the column's height.
  EXPECT_EQ(choice->fitted.size(), 9u);
}

TEST(KinematicFit, RecoversTheXarmFromThirtyNoisyPoints) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  const auto truth = xarm_truth();
  const auto points = testing::touched_points(m, truth, {});
  auto r = fit_kinematics(m, points);
  ASSERT_TRUE(r) << r.error().message;
  print("xarm, 30 points", *r);
  EXPECT_GT(r->before.rms, 5 * kMm);  // the wrong arm misses by millimetres
  EXPECT_LT(r->after.rms, 0.3 * kMm);
  EXPECT_LT(r->after.max, 0.6 * kMm);
  expect_recovered(m, truth, *r, arm::Protocol::robot_commands);
}

TEST(KinematicFit, RecoversTheXarmFromTenPoints) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  const auto truth = xarm_truth();
  const auto points = testing::touched_points(m, truth, {.count = 10, .seed = 7});
  auto r = fit_kinematics(m, points);
  ASSERT_TRUE(r) << r.error().message;
  print("xarm, 10 points", *r);
  expect_recovered(m, truth, *r, arm::Protocol::robot_commands);
}

TEST(KinematicFit, RecoversTheScaraFromThirtyNoisyPoints) {
  const arm::ArmModel m = arm::testing::shipped("scara");
  const auto truth = scara_truth();
  const auto points = testing::touched_points(m, truth, {.seed = 3});
  auto r = fit_kinematics(m, points);
  ASSERT_TRUE(r) << r.error().message;
  print("scara, 30 points", *r);
  EXPECT_GT(r->before.rms, 10 * kMm);
  EXPECT_LT(r->after.rms, 0.3 * kMm);
  expect_recovered(m, truth, *r, arm::Protocol::joint_bus);
}

TEST(KinematicFit, ManySeedsOnBothArms) {
  // The recovery is no accident of one seed.
  for (unsigned seed = 10; seed < 20; ++seed) {
    SCOPED_TRACE(seed);
    const arm::ArmModel x = arm::testing::shipped("xarm");
    auto rx = fit_kinematics(x, testing::touched_points(x, xarm_truth(), {.count = 20, .seed = seed}));
    ASSERT_TRUE(rx) << rx.error().message;
    expect_recovered(x, xarm_truth(), *rx, arm::Protocol::robot_commands);
    const arm::ArmModel s = arm::testing::shipped("scara");
    auto rs = fit_kinematics(s, testing::touched_points(s, scara_truth(), {.seed = seed}));
    ASSERT_TRUE(rs) << rs.error().message;
    expect_recovered(s, scara_truth(), *rs, arm::Protocol::joint_bus);
  }
}

TEST(KinematicFit, APointTouchedAtTheWrongPlaceStandsOut) {
  // One point 15 mm from where it was said to be (the wrong mark, a slipped tool): the fit
  // cannot absorb it, and the report names it as the worst.
  const arm::ArmModel m = arm::testing::shipped("xarm");
  auto points = testing::touched_points(m, xarm_truth(), {.count = 20, .seed = 9});
  points[6].position.y() += 15 * kMm;
  auto r = fit_kinematics(m, points);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->after.worst, "P7");
  EXPECT_GT(r->after.max, 5 * kMm);
  for (const PointResidual& p : r->after.points) {
    if (p.name == "P7") continue;
    EXPECT_LT(p.distance, r->after.max / 2) << p.name;
  }
}

TEST(KinematicFit, TooFewPointsAreRefusedNamingAParameter) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  const auto points = testing::touched_points(m, xarm_truth(), {.count = 2});
  auto r = fit_kinematics(m, points);
  ASSERT_FALSE(r);
  const auto* d = r.error().detail_as<Unidentifiable>();
  ASSERT_NE(d, nullptr) << r.error().message;
  EXPECT_NE(r.error().message.find(d->parameter.name), std::string::npos) << r.error().message;
  EXPECT_EQ(d->condition, 0);  // 6 equations, 8 parameters
}

TEST(KinematicFit, EnoughRankButFewerThanTenPointsIsRefused) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  const auto points = testing::touched_points(m, xarm_truth(), {.count = 6});
  auto r = fit_kinematics(m, points);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().detail_as<Unidentifiable>(), nullptr) << r.error().message;
  EXPECT_NE(r.error().message.find("at least 10"), std::string::npos) << r.error().message;
}

TEST(KinematicFit, TheXarmElbowUnmovedIsRefusedNamingIt) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  const int elbow = *m.find_joint("servo4");
  const auto points = testing::touched_points(m, xarm_truth(), {.unmoved_joint = elbow});
  auto r = fit_kinematics(m, points);
  ASSERT_FALSE(r);
  const auto* d = r.error().detail_as<Unidentifiable>();
  ASSERT_NE(d, nullptr) << r.error().message;
  std::vector<Parameter> named = d->same_as;
  named.push_back(d->parameter);
  EXPECT_TRUE(names_any(named, "servo4")) << r.error().message;
  EXPECT_NE(r.error().message.find("servo4 hardly moved between them"), std::string::npos) << r.error().message;
  std::cout << r.error().message << "\n";
}

TEST(KinematicFit, TheScaraWristPitchUnmovedAtZeroIsRefusedNamingTheAlignedJoints) {
  // With SKE at 0 the wrist's yaw (UAJ) and roll (SKF) axes are one line: their zeros
  // cannot be told apart.
  const arm::ArmModel m = arm::testing::shipped("scara");
  testing::PointOptions o;
  o.unmoved_joint = *m.find_joint("SKE");
  o.unmoved_at_middle = true;
  // The truth's SKE error would tilt the wrist off the aligned pose: none here.
  auto truth = scara_truth();
  truth.zero_error.erase("SKE");
  const auto points = testing::touched_points(m, truth, o);
  for (const auto& p : points) ASSERT_NEAR(p.joints[std::size_t(o.unmoved_joint)], 0.0, 1e-12);
  auto r = fit_kinematics(m, points);
  ASSERT_FALSE(r);
  const auto* d = r.error().detail_as<Unidentifiable>();
  ASSERT_NE(d, nullptr) << r.error().message;
  std::vector<Parameter> named = d->same_as;
  named.push_back(d->parameter);
  EXPECT_TRUE(names_any(named, "zero of UAJ")) << r.error().message;
  EXPECT_TRUE(names_any(named, "zero of SKF")) << r.error().message;
  std::cout << r.error().message << "\n";
}

TEST(KinematicFit, TheScaraElbowUnmovedIsRefused) {
  const arm::ArmModel m = arm::testing::shipped("scara");
  const auto points = testing::touched_points(m, scara_truth(), {.unmoved_joint = *m.find_joint("UAE")});
  auto r = fit_kinematics(m, points);
  ASSERT_FALSE(r);
  const auto* d = r.error().detail_as<Unidentifiable>();
  ASSERT_NE(d, nullptr) << r.error().message;
  std::cout << r.error().message << "\n";
}

TEST(KinematicFit, BadInputIsRefusedNamingThePoint) {
  const arm::ArmModel m = arm::testing::shipped("xarm");
  auto points = testing::touched_points(m, xarm_truth(), {.count = 12});
  points[4].joints.pop_back();
  auto r = fit_kinematics(m, points);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("P5"), std::string::npos) << r.error().message;
  points = testing::touched_points(m, xarm_truth(), {.count = 12});
  points[2].position.x() = std::nan("");
  r = fit_kinematics(m, points);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("P3"), std::string::npos) << r.error().message;
  EXPECT_FALSE(fit_kinematics(m, std::vector<TouchedPoint>{}));
  points = testing::touched_points(m, xarm_truth(), {.count = 12});
  FitOptions o;
  o.parameters = {zero_parameter(m, 0), zero_parameter(m, 0)};
  r = fit_kinematics(m, points, o);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("twice"), std::string::npos) << r.error().message;
}

TEST(KinematicFit, AFitAskedForAnInvisibleParameterIsRefused) {
  // The xArm's roll zero does not move the tool point at all.
  const arm::ArmModel m = arm::testing::shipped("xarm");
  const auto points = testing::touched_points(m, xarm_truth(), {});
  FitOptions o;
  o.parameters = {zero_parameter(m, 0), zero_parameter(m, *m.find_joint("servo2"))};
  auto r = fit_kinematics(m, points, o);
  ASSERT_FALSE(r);
  const auto* d = r.error().detail_as<Unidentifiable>();
  ASSERT_NE(d, nullptr) << r.error().message;
  EXPECT_EQ(d->parameter.name, "zero of servo2");
}

}  // namespace
}  // namespace armctl::calibration

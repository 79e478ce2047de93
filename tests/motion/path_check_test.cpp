// The path check on both shipped arms: a reachable LIN passes with continuous joints that
// reproduce the path, a LIN leaving the workspace and a joint leaving its limits are refused
// naming where and which joint, a path near a singularity is slowed, too near it refused,
// and through it refused as a jump.
#include "motion/path_check.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "motion/scara_kinematics.hpp"
#include "motion/urdf_chain.hpp"
#include "motion/xarm_kinematics.hpp"

namespace armctl::motion {
namespace {

using ::testing::HasSubstr;
using ::testing::MatchesRegex;
constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180; }

// A shipped arm: its kinematics from the URDF and the arm file's velocity and acceleration
// limits (config/<arm>.arm.json; the URDF's position limits are the arm file's too).
struct TestArm {
  std::unique_ptr<Kinematics> kinematics;
  std::vector<PathLimits> limits;
  bool nearest_orientation = false;
};

TestArm shipped(const std::string& arm) {
  auto chain = read_urdf_chain_file(std::string(ARMCTL_SOURCE_DIR) + "/config/" + arm + ".urdf", "base_link", "tool");
  if (!chain) throw std::runtime_error(chain.error().message);
  const auto positions = urdf_position_limits(*chain);
  const bool xarm = arm == "xarm";
  auto k = (xarm ? make_xarm_kinematics : make_scara_kinematics)(*chain, positions);
  if (!k) throw std::runtime_error(k.error().message);
  TestArm out;
  out.kinematics = std::move(k).value();
  out.nearest_orientation = xarm;
  // velocity, acceleration per chain joint as in the arm files
  const std::vector<std::pair<double, double>> rates =
      xarm ? std::vector<std::pair<double, double>>(5, {deg(180), deg(720)})
           : std::vector<std::pair<double, double>>{{0.06, 0.3},           {deg(60), deg(240)},  {deg(90), deg(480)},
                                                    {deg(120), deg(600)}, {deg(120), deg(600)}, {deg(120), deg(600)}};
  for (std::size_t j = 0; j < positions.size(); ++j) {
    const bool prismatic = chain->joints[j].type == ChainJointType::prismatic;
    out.limits.push_back(PathLimits{positions[j].lower, positions[j].upper, rates[j].first, rates[j].second,
                                    chain->joints[j].name, prismatic ? Dimension::length : Dimension::angle});
  }
  return out;
}

JointVector joints(std::initializer_list<double> values) {
  JointVector q(int(values.size()));
  int i = 0;
  for (double v : values) q[i++] = v;
  return q;
}

PathSegment lin_to(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation, double speed = 0.05) {
  PathSegment s;
  s.target.position = position;
  s.target.orientation = orientation;
  s.speed = speed;
  return s;
}

CartesianPath built(const Pose& start, const std::vector<PathSegment>& segments) {
  auto path = build_cartesian_path(start, segments);
  if (!path) throw std::runtime_error(path.error().message);
  return std::move(path).value();
}

Pose tool_identity() { return Pose{}; }

// Every sample's joints reach the path's position (and, on the 6-joint SCARA, orientation);
// successive samples are within the stated bounds; joints_at interpolates between them.
void expect_follows(const CartesianPath& path, const TestArm& arm, const CheckedPath& c, bool orientation) {
  ASSERT_EQ(c.s.size(), c.joints.size());
  ASSERT_EQ(c.s.size(), c.dq_ds.size());
  ASSERT_EQ(c.s.size(), c.rate_limit.size());
  EXPECT_EQ(c.s.front(), 0);
  EXPECT_EQ(c.s.back(), path.duration());
  double worst_position = 0, worst_rotation = 0, worst_step = 0, worst_joint_step = 0, worst_interpolation = 0;
  for (std::size_t i = 0; i < c.s.size(); ++i) {
    const Pose want = path.at(c.s[i]);
    const Pose got = arm.kinematics->forward(c.joints[i]);
    worst_position = std::max(worst_position, (got.position - want.position).norm());
    if (orientation) worst_rotation = std::max(worst_rotation, got.orientation.angularDistance(want.orientation));
    if (i == 0) continue;
    EXPECT_GE(c.s[i], c.s[i - 1]);
    worst_step = std::max(worst_step, (path.at(c.s[i]).position - path.at(c.s[i - 1]).position).norm());
    worst_joint_step = std::max(worst_joint_step, (c.joints[i] - c.joints[i - 1]).cwiseAbs().maxCoeff());
    const double mid = (c.s[i] + c.s[i - 1]) / 2;
    worst_interpolation = std::max(worst_interpolation, (c.joints_at(mid) - c.joints_at(mid, c.joints[i])).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst_position, 1e-9);
  EXPECT_LT(worst_rotation, 1e-9);
  EXPECT_LE(worst_step, kPathSampleLength + 1e-15);
  EXPECT_LE(worst_joint_step, kPathSampleJointAngle + 1e-15);
  // The interpolation's derivative against the samples' (and a central difference of it).
  double worst_rate = 0, scale = 0;
  for (std::size_t i = 1; i + 1 < c.s.size(); ++i) {
    if (c.s[i] == c.s[i - 1] || c.s[i] == c.s[i + 1]) continue;  // a rest: one-sided on each side
    const auto j = c.joints_with_rates(c.s[i]);
    EXPECT_LT((j.position - c.joints[i]).cwiseAbs().maxCoeff(), 1e-12);
    worst_rate = std::max(worst_rate, (j.dq_ds - c.dq_ds[i]).cwiseAbs().maxCoeff());
    scale = std::max(scale, c.dq_ds[i].cwiseAbs().maxCoeff());
    EXPECT_LE(c.rate_limit_at(c.s[i]), c.rate_limit[i]);
  }
  EXPECT_LE(worst_rate, 1e-9 * std::max(1.0, scale));
  EXPECT_LT(worst_interpolation, 1e-5);  // cubic Hermite between samples at most 1 mm / 1 deg apart
  std::printf("interpolation error %.3g rad over %zu samples\n", worst_interpolation, c.s.size());
}

TEST(PathCheck, XarmReachableLinPassesWithContinuousJoints) {
  const TestArm arm = shipped("xarm");
  const JointVector start = joints({deg(-20), deg(20), deg(40), deg(50), deg(10)});
  const Pose from = arm.kinematics->forward(start);
  // 60 mm sideways and 30 mm down, the tool's pitch and roll as at the start: on the xArm the
  // yaw follows the position (nearest orientation).
  const CartesianPath path =
      built(from, {lin_to(from.position + Eigen::Vector3d(0.02, 0.06, -0.03), from.orientation)});
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, true);
  ASSERT_TRUE(checked.ok()) << checked.error().message;
  expect_follows(path, arm, *checked, false);
  EXPECT_LT((checked->joints.front() - start).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT(checked->max_rate, 1);  // 50 mm/s needs less than the 180 deg/s of any servo here
  EXPECT_TRUE(checked->slowed.empty());
  // Tool pitch and roll stay as at the start (Arm::tool_rpy's form: roll = the wrist's roll).
  const double pitch_sum0 = start[1] + start[2] + start[3];
  for (const JointVector& q : checked->joints) {
    EXPECT_NEAR(q[1] + q[2] + q[3], pitch_sum0, 1e-6);
    EXPECT_NEAR(q[4], start[4], 1e-6);
  }
}

TEST(PathCheck, ScaraReachableLinAndBlendedCornerPass) {
  const TestArm arm = shipped("scara");
  const JointVector start = joints({0.1, deg(30), deg(60), deg(-30), deg(45), deg(20)});
  const Pose from = arm.kinematics->forward(start);
  PathSegment first = lin_to(from.position + Eigen::Vector3d(0.03, -0.06, 0.02), from.orientation);
  first.zone = 0.01;
  PathSegment second = lin_to(from.position + Eigen::Vector3d(0.03, -0.13, 0.02),
                              from_rpy({0.1, 0, 0.2}) * from.orientation);
  const CartesianPath path = built(from, {first, second});
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, false);
  ASSERT_TRUE(checked.ok()) << checked.error().message;
  expect_follows(path, arm, *checked, true);
  EXPECT_EQ(path.rests().size(), 1u);  // blended: no stop at the corner
}

TEST(PathCheck, TheToolFrameIsAppliedAsArmInverseDoes) {
  const TestArm arm = shipped("scara");
  Pose tool;
  tool.position = {0.02, 0, 0.03};  // a longer gripper
  tool.orientation = from_rpy({0, 0.2, 0});
  const JointVector start = joints({0.1, deg(30), deg(60), deg(-30), deg(45), deg(20)});
  Pose from = arm.kinematics->forward(start);
  from.position += from.orientation * tool.position;
  from.orientation = from.orientation * tool.orientation;
  const CartesianPath path = built(from, {lin_to(from.position + Eigen::Vector3d(0, 0.05, 0), from.orientation)});
  auto checked = check_path(path, *arm.kinematics, tool, start, arm.limits, false);
  ASSERT_TRUE(checked.ok()) << checked.error().message;
  for (std::size_t i = 0; i < checked->s.size(); i += 7) {
    const Pose flange = arm.kinematics->forward(checked->joints[i]);
    EXPECT_LT((flange.position + flange.orientation * tool.position - path.at(checked->s[i]).position).norm(), 1e-9);
  }
  // Without the tool frame the same start pose is not where the arm is.
  auto wrong = check_path(path, *arm.kinematics, Pose{}, start, arm.limits, false);
  ASSERT_FALSE(wrong.ok());
  EXPECT_THAT(wrong.error().message, HasSubstr("the path does not start where the arm is: joint"));
}

TEST(PathCheck, LinLeavingTheWorkspaceIsRefusedNamingWhere) {
  const TestArm arm = shipped("xarm");
  const JointVector start = joints({0, deg(20), deg(40), deg(50), 0});
  const Pose from = arm.kinematics->forward(start);
  PathSegment out = lin_to(from.position + Eigen::Vector3d(0.3, 0, 0), from.orientation);
  const CartesianPath path = built(from, {lin_to(from.position + Eigen::Vector3d(0, 0.02, 0), from.orientation), out});
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, true);
  ASSERT_FALSE(checked.ok());
  EXPECT_EQ(checked.error().kind, ErrorKind::invalid_argument);
  EXPECT_THAT(checked.error().message,
              MatchesRegex("segment 2 \\(LIN\\): at [0-9]+ % \\(x [-0-9.]+ y [-0-9.]+ z [-0-9.]+ mm\\): .*"));
  EXPECT_THAT(checked.error().message, HasSubstr("pose beyond reach by"));
}

TEST(PathCheck, JointLeavingItsLimitsIsRefusedNamingTheJoint) {
  TestArm arm = shipped("xarm");
  const JointVector start = joints({0, deg(20), deg(40), deg(50), 0});
  const Pose from = arm.kinematics->forward(start);
  // Sideways: the base turns towards +y. With servo6 narrowed to +-20 deg the path leaves it.
  const CartesianPath path = built(from, {lin_to(from.position + Eigen::Vector3d(0, 0.12, 0), from.orientation)});
  arm.limits[0].lower = deg(-20);
  arm.limits[0].upper = deg(20);
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, true);
  ASSERT_FALSE(checked.ok());
  EXPECT_THAT(checked.error().message,
              MatchesRegex("segment 1 \\(LIN\\): at [0-9]+ % \\(x [-0-9.]+ y [-0-9.]+ z [-0-9.]+ mm\\): joint servo6 "
                           "would be at 20\\.[0-9] deg, allowed -20\\.0\\.\\.20\\.0 deg"));
  // The same, typed: the segment, where on it (fraction and tool point), the joint.
  const PathRefusal* r = path_refusal_of(checked.error());
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->segment, 0);
  EXPECT_EQ(r->kind, SegmentKind::lin);
  ASSERT_TRUE(r->fraction && r->point);
  EXPECT_GT(*r->fraction, 0);
  EXPECT_LT(*r->fraction, 1);
  EXPECT_NEAR((*r->point - path.at(*r->fraction * path.duration()).position).norm(), 0, 1e-9);
  EXPECT_EQ(r->joint, 0);
  EXPECT_EQ(r->joint_name, "servo6");
  EXPECT_EQ("segment 1 (LIN): " + r->reason, checked.error().message);
}

TEST(PathCheck, JointAtTheKinematicsLimitIsRefusedNamingTheJoint) {
  // The SCARA's Z stops at its 0 mm: a LIN down past it.
  const TestArm arm = shipped("scara");
  const JointVector start = joints({0.01, deg(30), deg(60), deg(-30), deg(45), deg(20)});
  const Pose from = arm.kinematics->forward(start);
  const CartesianPath path = built(from, {lin_to(from.position + Eigen::Vector3d(0, 0, -0.03), from.orientation)});
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, false);
  ASSERT_FALSE(checked.ok());
  EXPECT_THAT(checked.error().message, HasSubstr("segment 1 (LIN): at 33 %"));
  EXPECT_THAT(checked.error().message, HasSubstr("joint Z"));
}

// A LIN of the xArm's tool across its base axis at `offset` from it, approach straight up.
struct AcrossTheBase {
  CartesianPath path;
  JointVector start;
};
AcrossTheBase across_the_base(const TestArm& arm, double offset) {
  const Eigen::Quaterniond up = from_rpy({0, -kPi / 2, 0});
  Pose from;
  from.position = {offset, -0.04, 0.3};
  from.orientation = up;
  IkRequest request{from, true};
  auto solutions = arm.kinematics->inverse(request, JointVector::Zero(5));
  if (!solutions) throw std::runtime_error(solutions.error().message);
  JointVector start = solutions->front().joints;
  from = arm.kinematics->forward(start);
  return {built(from, {lin_to({offset, 0.04, 0.3}, from.orientation)}), start};
}

TEST(PathCheck, NearASingularityThePathIsSlowed) {
  const TestArm arm = shipped("xarm");
  // 10 mm from the base axis at 50 mm/s the base turns at up to 5 rad/s: slowed to about
  // 3.14 / 5 = 63 %.
  const auto [path, start] = across_the_base(arm, 0.01);
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, true);
  ASSERT_TRUE(checked.ok()) << checked.error().message;
  expect_follows(path, arm, *checked, false);
  EXPECT_NEAR(checked->max_rate, deg(180) / (0.05 / 0.01), 0.01);
  ASSERT_EQ(checked->slowed.size(), 1u);
  const SlowSpot& spot = checked->slowed[0];
  EXPECT_EQ(spot.segment, 0);
  EXPECT_NEAR(spot.rate, checked->max_rate, 1e-12);
  EXPECT_NEAR(spot.at_s, path.duration() / 2, 0.01);  // nearest the axis
  EXPECT_LT(spot.from_s, spot.at_s);
  EXPECT_GT(spot.to_s, spot.at_s);
  EXPECT_EQ(spot.singularity, Singularity::over_base_axis);
  EXPECT_THAT(spot.message, MatchesRegex("segment 1 \\(LIN\\): at 50 % \\(x 10.0 y [-]?0.0 z 300.0 mm\\): slowed to "
                                         "6[0-9] % of the programmed speed: joint servo[62] would need .*"
                                         "near a singularity \\(tool over the base axis\\)"));
  // Far from the axis nothing is slowed.
  const auto [far, far_start] = across_the_base(arm, 0.05);
  auto fast = check_path(far, *arm.kinematics, tool_identity(), far_start, arm.limits, true);
  ASSERT_TRUE(fast.ok()) << fast.error().message;
  EXPECT_TRUE(fast->slowed.empty());
  EXPECT_GT(fast->max_rate, 1);
}

TEST(PathCheck, TooNearASingularityIsRefusedAtTheFloor) {
  const TestArm arm = shipped("xarm");
  // 0.1 mm from the axis the base would turn at 500 rad/s: below 1 % it would still need 5 rad/s.
  const auto [path, start] = across_the_base(arm, 0.0001);
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, true);
  ASSERT_FALSE(checked.ok());
  EXPECT_THAT(checked.error().message,
              MatchesRegex("segment 1 \\(LIN\\): at 50 % \\(x 0.1 y [-]?0.[0-9] z 300.0 mm\\): joint servo[62] would need "
                           "[0-9.]+ deg/s at 1 % of the programmed speed, allowed 180.0 deg/s near a singularity \\(tool "
                           "over the base axis\\)"));
}

TEST(PathCheck, OverTheBaseAxisWithTheApproachUpTheXarmLeansOverWithoutTurning) {
  // Exactly across the axis the base need not turn: the arm leans over to the other side
  // (reaching back), continuously.
  const TestArm arm = shipped("xarm");
  const auto [path, start] = across_the_base(arm, 0);
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, true);
  ASSERT_TRUE(checked.ok()) << checked.error().message;
  expect_follows(path, arm, *checked, false);
  EXPECT_NEAR(checked->joints.back()[0], start[0], 1e-9);
}

// The xArm starts straight up, every servo centred: the arm stretched, the tool on the
// base axis. A line sideways needs the base to jump to its heading; a line straight down
// needs the elbow to bend as the square root of the distance (unbounded speed at first, which
// the check's finite differences turned into a 10 mm line slowed to 56.6 s). Both are refused
// at the start, saying to move away with a joint move first; a few degrees off the
// singular pose, the same line straight down passes.
TEST(PathCheck, ALineThatCannotLeaveASingularStartIsRefusedSayingWhatToDo) {
  const TestArm arm = shipped("xarm");
  const JointVector straight_up = JointVector::Zero(5);
  ASSERT_EQ(arm.kinematics->singularity(straight_up, kSingularStart), Singularity::arm_stretched);
  const Pose top = arm.kinematics->forward(straight_up);
  const std::string what_to_do =
      "a straight line cannot start there; move the arm away from it first with a joint move \\(PTP: a move to a "
      "tool point without a straight line, or a ptp line before the path\\), then start the path";
  const CartesianPath sideways = built(top, {lin_to(Eigen::Vector3d(0.18, 0.04, 0.10), top.orientation, 0.04)});
  auto jump = check_path(sideways, *arm.kinematics, tool_identity(), straight_up, arm.limits, true);
  ASSERT_FALSE(jump.ok());
  EXPECT_THAT(jump.error().message,
              MatchesRegex("segment 1 \\(LIN\\): at 0 % \\(x 0.0 y 0.0 z [0-9.]+ mm\\): the path starts at a singularity "
                           "\\(arm stretched or folded\\), where the joints would jump: joint servo6 from 0.0 deg to "
                           "[0-9.]+ deg: " + what_to_do));
  const CartesianPath down = built(top, {lin_to(top.position - Eigen::Vector3d(0, 0, 0.01), top.orientation)});
  auto crawl = check_path(down, *arm.kinematics, tool_identity(), straight_up, arm.limits, true);
  ASSERT_FALSE(crawl.ok());
  EXPECT_THAT(crawl.error().message,
              MatchesRegex("segment 1 \\(LIN\\): at 0 % .*: the path starts at a singularity \\(arm stretched or "
                           "folded\\), where joint servo[0-9] would have to move faster the closer the tool is to it "
                           "\\([0-9.]+ deg/s at full speed over the first step, allowed 180.0 deg/s\\): " + what_to_do));
  // Leaning over and bent by 20 deg (the wrist keeping the tool up), the same line down passes.
  const JointVector bent = joints({0, deg(10), deg(20), deg(-30), 0});
  ASSERT_EQ(arm.kinematics->singularity(bent, kSingularStart), Singularity::none);
  const Pose from = arm.kinematics->forward(bent);
  const CartesianPath down_bent = built(from, {lin_to(from.position - Eigen::Vector3d(0, 0, 0.01), from.orientation)});
  auto passes = check_path(down_bent, *arm.kinematics, tool_identity(), bent, arm.limits, true);
  ASSERT_TRUE(passes.ok()) << passes.error().message;
  expect_follows(down_bent, arm, *passes, false);
}

// One joint whose only solution jumps by 2 at x = 0.05 m: a configuration change.
class JumpingKinematics final : public Kinematics {
 public:
  std::string_view family() const override { return "scara"; }
  int joint_count() const override { return 1; }
  Pose forward(const JointVector& q) const override {
    Pose p;
    p.position.x() = q[0] < 1 ? q[0] : q[0] - 2;
    return p;
  }
  Result<std::vector<IkSolution>> inverse(const IkRequest& request, const JointVector&) const override {
    const double x = request.target.position.x();
    IkSolution s{joints({x < 0.05 ? x : x + 2}), Configuration{x < 0.05 ? Elbow::left : Elbow::right, {}, {}}};
    return std::vector<IkSolution>{s};
  }
  Jacobian jacobian(const JointVector&) const override { return Jacobian::Zero(6, 1); }
  Singularity singularity(const JointVector&, double) const override { return Singularity::none; }
};

TEST(PathCheck, ASolutionThatJumpsIsRefusedNamingTheConfigurations) {
  const JumpingKinematics kinematics;
  const std::vector<PathLimits> limits{{-10, 10, 1, 10, "J", Dimension::length}};
  const CartesianPath path = built(Pose{}, {lin_to({0.1, 0, 0}, Eigen::Quaterniond::Identity())});
  auto checked = check_path(path, kinematics, Pose{}, joints({0}), limits, false);
  ASSERT_FALSE(checked.ok());
  EXPECT_THAT(checked.error().message,
              MatchesRegex("segment 1 \\(LIN\\): at 50 % \\(x 50.0 y 0.0 z 0.0 mm\\): the joints would jump: joint J "
                           "from 50.0 mm to 2050.0 mm, a change of configuration \\(elbow left -> elbow right\\); the "
                           "arm cannot follow the path through there.*"));
}

TEST(PathCheck, JointWhoseSolutionEndsAtItsLimitIsRefusedNamingTheJoint) {
  // The SCARA folding its elbow (UAE, limited to 145 deg) as the tool comes in towards the
  // shoulder: past the limit only the other elbow solves, far away.
  const TestArm arm = shipped("scara");
  const JointVector start = joints({0.1, deg(0), deg(120), deg(-120), deg(45), deg(20)});
  const Pose from = arm.kinematics->forward(start);
  const CartesianPath path = built(from, {lin_to(from.position * 0.5 + Eigen::Vector3d(0, 0, from.position.z() * 0.5),
                                                 from.orientation)});
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, false);
  ASSERT_FALSE(checked.ok());
  EXPECT_THAT(checked.error().message, MatchesRegex("segment 1 \\(LIN\\): at [0-9]+ % .*joint UAE.*145.0.*"));
}

TEST(PathCheck, ScaraWristNearlyAlignedIsSlowed) {
  const TestArm arm = shipped("scara");
  // The wrist's tilt (SKE, 2 deg) turned a quarter turn about the vertical (UAJ and SKF
  // +90 deg, which keeps the approach: with the wrist aligned only UAJ - SKF counts): the
  // slerp between the two orientations passes the wrist within 2 deg * cos(45 deg) = 1.4 deg
  // of aligned, where UAJ and SKF turn fast.
  const JointVector start = joints({0.1, deg(30), deg(60), deg(-60), deg(2), deg(80)});
  const Pose from = arm.kinematics->forward(start);
  const JointVector other = joints({0.1, deg(30), deg(60), deg(30), deg(2), deg(170)});
  const Pose to = arm.kinematics->forward(other);
  const CartesianPath path = built(from, {lin_to(to.position, to.orientation)});
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, false);
  ASSERT_TRUE(checked.ok()) << checked.error().message;
  expect_follows(path, arm, *checked, true);
  ASSERT_EQ(checked->slowed.size(), 1u);
  EXPECT_EQ(checked->slowed[0].singularity, Singularity::wrist_aligned);
  EXPECT_LT(checked->max_rate, 0.5);
  EXPECT_GT(checked->max_rate, kMinPathRate);
  EXPECT_THAT(checked->slowed[0].message, HasSubstr("near a singularity (wrist axes aligned)"));
  std::printf("%s\n", checked->slowed[0].message.c_str());
}

TEST(PathCheck, RestsAppearTwiceWithOneSidedDerivatives) {
  const TestArm arm = shipped("scara");
  const JointVector start = joints({0.1, deg(30), deg(60), deg(-30), deg(45), deg(20)});
  const Pose from = arm.kinematics->forward(start);
  const CartesianPath path = built(from, {lin_to(from.position + Eigen::Vector3d(0.03, 0, 0), from.orientation),
                                          lin_to(from.position + Eigen::Vector3d(0.03, 0.03, 0), from.orientation)});
  auto checked = check_path(path, *arm.kinematics, tool_identity(), start, arm.limits, false);
  ASSERT_TRUE(checked.ok()) << checked.error().message;
  const double corner = path.rests()[0];
  int count = 0;
  std::size_t first = 0;
  for (std::size_t i = 0; i < checked->s.size(); ++i)
    if (checked->s[i] == corner) {
      if (count++ == 0) first = i;
    }
  ASSERT_EQ(count, 2);
  // Before the corner the tool moves along x, after it along y: the joints' directions differ.
  EXPECT_GT((checked->dq_ds[first] - checked->dq_ds[first + 1]).norm(), 0.1);
  EXPECT_EQ(checked->joints[first], checked->joints[first + 1]);
}

TEST(PathCheck, BadArgumentsAreRefused) {
  const TestArm arm = shipped("xarm");
  const JointVector start = joints({0, deg(20), deg(40), deg(50), 0});
  const Pose from = arm.kinematics->forward(start);
  const CartesianPath path = built(from, {lin_to(from.position + Eigen::Vector3d(0, 0.02, 0), from.orientation)});
  auto few = check_path(path, *arm.kinematics, Pose{}, start, std::span(arm.limits).first(4), true);
  EXPECT_THAT(few.error().message, HasSubstr("4 joint limits given for a chain of 5 joints"));
  auto short_start = check_path(path, *arm.kinematics, Pose{}, joints({0, 0}), arm.limits, true);
  EXPECT_THAT(short_start.error().message, HasSubstr("2 start joints given for a chain of 5 joints"));
  std::vector<PathLimits> slow = arm.limits;
  slow[2].velocity = 0;
  EXPECT_THAT(check_path(path, *arm.kinematics, Pose{}, start, slow, true).error().message,
              HasSubstr("joint servo4: velocity and acceleration limits must be finite and > 0"));
  const JointVector elsewhere = joints({deg(10), deg(20), deg(40), deg(50), 0});
  EXPECT_THAT(check_path(path, *arm.kinematics, Pose{}, elsewhere, arm.limits, true).error().message,
              HasSubstr("the path does not start where the arm is: joint servo6 is at 10.0 deg, the path's start pose "
                        "needs 0.0 deg"));
}

}  // namespace
}  // namespace armctl::motion

// The kinematics at its edges: joint limits and whole turns, singular configurations,
// unreachable poses and their messages, the xArm's 5-joint orientation, chains of the wrong
// shape, bad requests, and the roll/pitch/yaw convention.
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "arm_files.hpp"

namespace armctl::motion {
namespace {

using ::testing::HasSubstr;
using testing::edited;
using testing::MakeKinematics;
using testing::urdf_text;
constexpr double kPi = std::numbers::pi;

double deg(double d) { return d * kPi / 180; }

JointVector joints(std::initializer_list<double> values) {
  JointVector q(int(values.size()));
  int i = 0;
  for (double v : values) q[i++] = v;
  return q;
}

void expect_reaches(const Kinematics& k, const Pose& target, const std::vector<IkSolution>& solutions) {
  ASSERT_FALSE(solutions.empty());
  for (const auto& s : solutions) {
    const Pose back = k.forward(s.joints);
    EXPECT_LT(testing::position_error(back.position, target.position), 1e-9);
    EXPECT_LT(testing::rotation_error(back.orientation.toRotationMatrix(), target.orientation.toRotationMatrix()), 1e-9);
  }
}

bool contains(const std::vector<IkSolution>& solutions, const JointVector& q) {
  for (const auto& s : solutions) {
    if ((s.joints - q).cwiseAbs().maxCoeff() < 1e-9) return true;
  }
  return false;
}

std::string error_of(const Result<std::vector<IkSolution>>& r) { return r.ok() ? "(solved)" : r.error().message; }

// --- roll, pitch, yaw -------------------------------------------------------------------

TEST(Rpy, IsYawThenPitchThenRollAboutFixedAxes) {
  const Eigen::Matrix3d r = from_rpy({0.1, 0.2, 0.3}).toRotationMatrix();
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_LT((r - expected).cwiseAbs().maxCoeff(), 1e-15);
  // Yaw 90 deg turns x onto y; pitch 90 deg turns x onto -z.
  EXPECT_LT((from_rpy({0, 0, kPi / 2}) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  EXPECT_LT((from_rpy({0, kPi / 2, 0}) * Eigen::Vector3d::UnitX() + Eigen::Vector3d::UnitZ()).norm(), 1e-15);
}

TEST(Rpy, RoundTrips) {
  testing::RandomJoints random({{-kPi, kPi}, {-kPi / 2, kPi / 2}, {-kPi, kPi}}, 7);
  for (int n = 0; n < 10000; ++n) {
    const JointVector a = random();
    const Rpy back = to_rpy(from_rpy({a[0], a[1], a[2]}));
    EXPECT_NEAR(back.roll, a[0], 1e-9);
    EXPECT_NEAR(back.pitch, a[1], 1e-9);
    EXPECT_NEAR(back.yaw, a[2], 1e-9);
  }
}

TEST(Rpy, PitchNinetyPutsTheTurnInYaw) {
  const Eigen::Quaterniond q = from_rpy({0.4, kPi / 2, 0.1});
  const Rpy r = to_rpy(q);
  EXPECT_NEAR(r.pitch, kPi / 2, 1e-9);
  EXPECT_EQ(r.roll, 0);
  EXPECT_LT(testing::rotation_error(from_rpy(r).toRotationMatrix(), q.toRotationMatrix()), 1e-9);
}

// --- SCARA ------------------------------------------------------------------------------

class Scara : public ::testing::Test {
 protected:
  std::unique_ptr<Kinematics> k = testing::shipped_kinematics("scara");
  JointVector zero = JointVector::Zero(6);
  Pose pose(std::initializer_list<double> q) { return k->forward(joints(q)); }
};

TEST_F(Scara, ZeroIsStretchedAlongXWithTheToolPointingOut) {
  const Pose p = k->forward(zero);
  EXPECT_LT((p.position - Eigen::Vector3d(0.685, 0, 0.2)).norm(), 1e-15);
  // Tool x = approach = +x; z along SKF's axis, down.
  const Eigen::Matrix3d r = p.orientation.toRotationMatrix();
  EXPECT_LT((r.col(0) - Eigen::Vector3d::UnitX()).norm(), 1e-15);
  EXPECT_LT((r.col(2) + Eigen::Vector3d::UnitZ()).norm(), 1e-15);
}

TEST_F(Scara, FourSolutionsElbowLeftRightWristFlipped) {
  const JointVector q = joints({0.1, 0.3, 0.8, 0.2, 0.5, 0.4});
  auto s = k->inverse(IkRequest{k->forward(q)}, zero);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_reaches(*k, k->forward(q), *s);
  EXPECT_EQ(s->size(), 4u);
  EXPECT_TRUE(contains(*s, q));
  int right = 0, flipped = 0;
  for (const auto& sol : *s) {
    right += *sol.configuration.elbow == Elbow::right;
    flipped += *sol.configuration.wrist_flipped;
    EXPECT_FALSE(sol.configuration.reaching_back.has_value());
    if ((sol.joints - q).cwiseAbs().maxCoeff() < 1e-9) {
      EXPECT_EQ(*sol.configuration.elbow, Elbow::right);  // UAE > 0: the elbow to the right
      EXPECT_FALSE(*sol.configuration.wrist_flipped);     // SKE > 0
    }
  }
  EXPECT_EQ(right, 2);
  EXPECT_EQ(flipped, 2);
}

TEST_F(Scara, JointsAtTheirLimitsAreReached) {
  for (const JointVector& q : {joints({0.0, deg(150), deg(-145), deg(170), deg(120), deg(-170)}),
                               joints({0.3, deg(-150), deg(145), deg(-170), deg(-120), deg(170)})}) {
    auto s = k->inverse(IkRequest{k->forward(q)}, q);
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_LT(((*s)[0].joints - q).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST_F(Scara, AnglesAreBroughtIntoTheLimitsByWholeTurns) {
  // UAJ at 165 deg, asked near -160 deg: -195 deg is nearer but outside; 165 deg it is.
  const JointVector q = joints({0.1, 0.3, 0.8, deg(165), 0.5, 0.4});
  JointVector near = q;
  near[3] = deg(-160);
  auto s = k->inverse(IkRequest{k->forward(q)}, near);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(contains(*s, q));
}

TEST_F(Scara, BeyondReachSaysByHowMuch) {
  // Tool along +x at 1 m: the wrist centre 175 mm behind it, 825 mm out; the arm reaches 510.
  auto s = k->inverse(IkRequest{Pose{{1.0, 0, 0.35}, k->forward(zero).orientation}}, zero);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().kind, ErrorKind::invalid_argument);
  EXPECT_THAT(s.error().message, HasSubstr("beyond reach by 315.0 mm"));
  EXPECT_THAT(s.error().message, HasSubstr("825.0 mm from the SHOULDER axis, the arm reaches 510.0 mm"));
}

TEST_F(Scara, ZOutsideItsTravelNamesTheJoint) {
  auto s = k->inverse(IkRequest{Pose{{0.5, 0, 0.55}, k->forward(zero).orientation}}, zero);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message, HasSubstr("no solution inside the joint limits"));
  EXPECT_THAT(s.error().message, HasSubstr("joint Z would be 350.0 mm, outside 0.0..300.0 mm"));
}

TEST_F(Scara, TighterLimitsFromTheArmFileAreKept) {
  auto limits = urdf_position_limits(testing::shipped_chain("scara"));
  limits[1] = {deg(-10), deg(10)};
  auto tight = make_scara_kinematics(testing::shipped_chain("scara"), limits);
  ASSERT_TRUE(tight.ok());
  auto s = (*tight)->inverse(IkRequest{pose({0.1, deg(30), deg(60), 0.2, 0.5, 0.4})}, zero);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message, HasSubstr("elbow right, wrist not flipped: joint SHOULDER would be 30.0 deg, "
                                           "outside -10.0..10.0 deg"));
}

TEST_F(Scara, SingularitiesAreNamed) {
  EXPECT_EQ(k->singularity(zero), Singularity::arm_stretched);
  EXPECT_EQ(k->singularity(joints({0.1, 0.3, deg(-144.99), 0.2, 0.5, 0.4})), Singularity::none);
  EXPECT_EQ(k->singularity(joints({0.1, 0.3, 0.0005, 0.2, 0.5, 0.4})), Singularity::arm_stretched);
  EXPECT_EQ(k->singularity(joints({0.1, 0.3, 1.0, 0.2, 0.0, 0.4})), Singularity::wrist_aligned);
  EXPECT_EQ(k->singularity(joints({0.1, 0.3, 1.0, 0.2, 0.01, 0.4})), Singularity::none);
  EXPECT_EQ(k->singularity(joints({0.1, 0.3, 1.0, 0.2, 0.01, 0.4}), 0.02), Singularity::wrist_aligned);
  EXPECT_EQ(k->singularity(joints({0.1, 0.3, 1.0, 0.2, 0.5, 0.4})), Singularity::none);
  EXPECT_STREQ(to_string(Singularity::wrist_aligned), "wrist axes aligned");
}

TEST_F(Scara, AlignedWristKeepsItsFirstJointWhereItIs) {
  // SKE = 0: UAJ and SKF in line, only their sum matters; UAJ stays at `near`.
  const JointVector q = joints({0.1, 0.3, 1.0, 0.2, 0.0, 0.4});
  JointVector near = q;
  near[3] = 0.5;
  auto s = k->inverse(IkRequest{k->forward(q)}, near);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_reaches(*k, k->forward(q), *s);
  EXPECT_NEAR((*s)[0].joints[3], 0.5, 1e-9);
  // At SKE = 0 SKF's axis points down, against UAJ's: UAJ - SKF is what counts (0.2 - 0.4).
  EXPECT_NEAR((*s)[0].joints[5], 0.7, 1e-9);
}

TEST_F(Scara, StretchedArmHasOneElbowSolution) {
  const JointVector q = joints({0.1, 0.3, 0.0, 0.2, 0.5, 0.4});
  auto s = k->inverse(IkRequest{k->forward(q)}, q);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_reaches(*k, k->forward(q), *s);
  EXPECT_EQ(s->size(), 2u);  // one elbow, two wrists
  EXPECT_TRUE(contains(*s, q));
}

TEST_F(Scara, JacobianLosesRankWhereSingular) {
  auto rank = [&](const JointVector& q) {
    return Eigen::FullPivLU<Eigen::MatrixXd>(k->jacobian(q)).setThreshold(1e-9).rank();
  };
  EXPECT_EQ(rank(joints({0.1, 0.3, 1.0, 0.2, 0.5, 0.4})), 6);
  EXPECT_EQ(rank(joints({0.1, 0.3, 0.0, 0.2, 0.5, 0.4})), 5);
  EXPECT_EQ(rank(joints({0.1, 0.3, 1.0, 0.2, 0.0, 0.4})), 5);
}

TEST_F(Scara, BadRequestsAreRefused) {
  const Pose good = k->forward(joints({0.1, 0.3, 1.0, 0.2, 0.5, 0.4}));
  Pose nan = good;
  nan.position.x() = std::nan("");
  EXPECT_THAT(error_of(k->inverse(IkRequest{nan}, zero)), HasSubstr("not finite"));
  Pose scaled = good;
  scaled.orientation.coeffs() *= 2;
  EXPECT_THAT(error_of(k->inverse(IkRequest{scaled}, zero)), HasSubstr("norm 2; it must be a unit quaternion"));
  EXPECT_THAT(error_of(k->inverse(IkRequest{good}, JointVector::Zero(3))), HasSubstr("3 joint values"));
  EXPECT_THROW(k->forward(JointVector::Zero(5)), ArmctlError);
}

// --- xArm -------------------------------------------------------------------------------

class Xarm : public ::testing::Test {
 protected:
  std::unique_ptr<Kinematics> k = testing::shipped_kinematics("xarm");
  JointVector zero = JointVector::Zero(5);
};

TEST_F(Xarm, ZeroStandsStraightUpWithTheApproachUp) {
  const Pose p = k->forward(zero);
  EXPECT_LT((p.position - Eigen::Vector3d(0, 0, 0.036 + 0.032 + 0.09765 + 0.0965 + 0.054 + 0.05)).norm(), 1e-15);
  EXPECT_LT((p.orientation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(to_rpy(p.orientation).pitch, -kPi / 2, 1e-9);
}

TEST_F(Xarm, ElbowUpAndDownFacingThePoint) {
  const JointVector q = joints({0.3, 0.3, 0.6, 0.3, 0.2});
  auto s = k->inverse(IkRequest{k->forward(q)}, zero);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_reaches(*k, k->forward(q), *s);
  ASSERT_TRUE(contains(*s, q));
  for (const auto& sol : *s) {
    if ((sol.joints - q).cwiseAbs().maxCoeff() < 1e-9) {
      EXPECT_EQ(*sol.configuration.elbow, Elbow::up);
      EXPECT_FALSE(*sol.configuration.reaching_back);
    }
    EXPECT_FALSE(sol.configuration.wrist_flipped.has_value());
  }
}

TEST_F(Xarm, BehindTheBaseRangeItReachesBack) {
  // Base at -30 deg, the arm leaning back over the top: the tool at azimuth 150 deg, where
  // the base cannot face (+-120 deg). Every solution reaches back.
  const JointVector q = joints({deg(-30), -0.5, -0.5, -0.3, 0.2});
  const Pose target = k->forward(q);
  EXPECT_NEAR(std::atan2(target.position.y(), target.position.x()), deg(150), 1e-9);
  auto s = k->inverse(IkRequest{target}, zero);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(contains(*s, q));
  for (const auto& sol : *s) {
    EXPECT_TRUE(*sol.configuration.reaching_back);
    EXPECT_NEAR(sol.joints[0], deg(-30), 1e-9);
  }
  expect_reaches(*k, target, *s);
}

TEST_F(Xarm, AnotherYawIsRefusedWithTheYawThatWorks) {
  // The tool point at azimuth 45 deg with a level approach (pitch sum 90 deg).
  const Pose reachable = k->forward(joints({deg(45), 0.4, 0.9, kPi / 2 - 1.3, 0}));
  EXPECT_NEAR(to_rpy(reachable.orientation).yaw, deg(45), 1e-9);
  EXPECT_NEAR(to_rpy(reachable.orientation).pitch, 0, 1e-9);
  const Rpy asked_rpy{to_rpy(reachable.orientation).roll, 0, 0};
  IkRequest request{Pose{reachable.position, from_rpy(asked_rpy)}};
  auto s = k->inverse(request, zero);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().kind, ErrorKind::invalid_argument);
  EXPECT_THAT(s.error().message, HasSubstr("orientation not reachable by this 5-joint arm: yaw must be 45.0 deg at "
                                           "this position (asked 0.0 deg; the approach is 45.0 deg out of the arm's plane)"));
  // Asked for the nearest orientation: the position exactly, yaw 45 deg, the rest kept.
  request.nearest_orientation = true;
  auto nearest = k->inverse(request, zero);
  ASSERT_TRUE(nearest.ok()) << nearest.error().message;
  for (const auto& sol : *nearest) {
    const Pose back = k->forward(sol.joints);
    EXPECT_LT((back.position - request.target.position).norm(), 1e-9);
    EXPECT_LT(testing::rotation_error(back.orientation.toRotationMatrix(), reachable.orientation.toRotationMatrix()), 1e-9);
  }
}

TEST_F(Xarm, BeyondReachSaysByHowMuchAtThisPitch) {
  // Approach level along +x, tool point 400 mm out: the wrist pitch axis 104 mm behind it,
  // (296, 32) mm from the shoulder axis.
  auto s = k->inverse(IkRequest{Pose{{0.4, 0, 0.1}, from_rpy({0, 0, 0})}}, zero);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message, HasSubstr("beyond reach by 103.6 mm at this tool pitch"));
  EXPECT_THAT(s.error().message, HasSubstr("joint servo3's axis would be 297.7 mm from joint servo5's"));
}

TEST_F(Xarm, OverTheBaseAxisTheBaseStaysWhereItIs) {
  // Straight up above the base, approach up: any base angle; the nearest is kept.
  const Pose target{{0, 0, 0.3}, k->forward(zero).orientation};
  JointVector near = zero;
  near[0] = 0.7;
  auto s = k->inverse(IkRequest{target}, near);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_reaches(*k, target, *s);
  EXPECT_NEAR((*s)[0].joints[0], 0.7, 1e-12);
  EXPECT_EQ(k->singularity((*s)[0].joints), Singularity::over_base_axis);
}

TEST_F(Xarm, OverTheBaseAxisTheApproachChoosesTheBase) {
  // Above the base, approach tilted towards +y: the base turns to face +y.
  const Pose target{{0, 0, 0.25}, from_rpy({0, deg(-45), deg(90)})};
  auto s = k->inverse(IkRequest{target}, zero);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_reaches(*k, target, *s);
  EXPECT_NEAR((*s)[0].joints[0], deg(90), 1e-9);
}

TEST_F(Xarm, SingularitiesAreNamed) {
  EXPECT_EQ(k->singularity(zero), Singularity::arm_stretched);
  EXPECT_EQ(k->singularity(joints({0.3, 0.4, 0.8, 0.2, 0.1})), Singularity::none);
  EXPECT_EQ(k->singularity(joints({0.3, 0.4, 0.0002, 0.2, 0.1})), Singularity::arm_stretched);
  EXPECT_STREQ(to_string(Singularity::over_base_axis), "tool over the base axis");
}

TEST_F(Xarm, ServoLimitsAreNamed) {
  // Reaching forward needs the base at 130 deg, reaching back at -50 deg with the shoulder
  // over the top: with the shoulder limited to 0..120 deg only facing would do, and the base
  // refuses.
  auto limits = urdf_position_limits(testing::shipped_chain("xarm"));
  limits[1] = {0, deg(120)};
  auto tight = make_xarm_kinematics(testing::shipped_chain("xarm"), limits);
  ASSERT_TRUE(tight.ok());
  const Eigen::Vector3d p(0.15 * std::cos(deg(130)), 0.15 * std::sin(deg(130)), 0.1);
  auto s = (*tight)->inverse(IkRequest{Pose{p, from_rpy({0, 0, deg(130)})}}, zero);
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.error().message, HasSubstr("joint servo6 would be 130.0 deg, outside -120.0..120.0 deg"));
  EXPECT_THAT(s.error().message, HasSubstr("reaching back: joint servo5 would be"));
}

// --- chains of the wrong shape ----------------------------------------------------------

std::string shape_error(MakeKinematics make, const std::string& text) {
  auto chain = read_urdf_chain(text, "base_link", "tool");
  if (!chain) return "URDF: " + chain.error().message;
  auto k = make(*chain, urdf_position_limits(*chain));
  if (k) return "(accepted)";
  EXPECT_EQ(k.error().kind, ErrorKind::invalid_config);
  return k.error().message;
}

std::string replace_nth(std::string text, const std::string& from, const std::string& to, int n) {
  std::size_t at = 0;
  for (int i = 0; i <= n; ++i) {
    at = text.find(from, i == 0 ? 0 : at + 1);
    if (at == std::string::npos) {
      ADD_FAILURE() << "no occurrence " << n << " of " << from;
      return text;
    }
  }
  return text.replace(at, from.size(), to);
}

TEST(KinematicShape, FamiliesNeedTheirJointCount) {
  EXPECT_THAT(shape_error(make_xarm_kinematics, urdf_text("scara")), HasSubstr("needs 5 chain joints"));
  EXPECT_THAT(shape_error(make_scara_kinematics, urdf_text("xarm")), HasSubstr("needs 6 chain joints"));
}

TEST(KinematicShape, ScaraRefusesATiltedElbowAxis) {
  const std::string text = replace_nth(urdf_text("scara"), "<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0.01 1\"/>", 2);
  EXPECT_THAT(shape_error(make_scara_kinematics, text), HasSubstr("joint UAE's axis is 0.5729 deg off joint Z's"));
}

TEST(KinematicShape, ScaraRefusesWristAxesThatDoNotMeet) {
  const std::string ske = "<origin xyz=\"0 0 0\" rpy=\"1.5707963267948966 0 0\"/>";
  EXPECT_THAT(shape_error(make_scara_kinematics, replace_nth(urdf_text("scara"), ske,
                                                              "<origin xyz=\"0.01 0 0\" rpy=\"1.5707963267948966 0 0\"/>", 0)),
              HasSubstr("the axes of joints UAJ and SKE pass 10 mm apart"));
  EXPECT_THAT(shape_error(make_scara_kinematics, replace_nth(urdf_text("scara"), ske,
                                                              "<origin xyz=\"0 0 0.01\" rpy=\"1.5707963267948966 0 0\"/>", 1)),
              HasSubstr("joint SKF's axis passes 10 mm from the wrist centre"));
}

TEST(KinematicShape, ScaraRefusesATurningColumn) {
  const std::string text = edited(urdf_text("scara"), "name=\"Z\" type=\"prismatic\"", "name=\"Z\" type=\"revolute\"");
  EXPECT_THAT(shape_error(make_scara_kinematics, text), HasSubstr("joint Z is revolute; joint 1 (Z) must be prismatic"));
}

TEST(KinematicShape, ScaraAcceptsOtherLengths) {
  // A calibrated URDF: longer forearm, another tool; the IK follows it.
  std::string text = replace_nth(urdf_text("scara"), "<origin xyz=\"0.255 0 0\"", "<origin xyz=\"0.2612 0 0\"", 1);
  text = edited(text, "<origin xyz=\"0.175 0 0\"", "<origin xyz=\"0.181 0.004 -0.01\"");
  auto chain = read_urdf_chain(text, "base_link", "tool");
  ASSERT_TRUE(chain.ok());
  auto k = make_scara_kinematics(*chain, urdf_position_limits(*chain));
  ASSERT_TRUE(k.ok()) << k.error().message;
  const JointVector q = joints({0.1, 0.3, 0.8, 0.2, 0.5, 0.4});
  EXPECT_NEAR((*k)->forward(JointVector::Zero(6)).position.x(), 0.255 + 0.2612 + 0.181, 1e-15);
  auto s = (*k)->inverse(IkRequest{(*k)->forward(q)}, q);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_reaches(**k, (*k)->forward(q), *s);
  EXPECT_TRUE(contains(*s, q));
}

TEST(KinematicShape, XarmRefusesAToolOffItsRollAxisOrSideways) {
  EXPECT_THAT(shape_error(make_xarm_kinematics, edited(urdf_text("xarm"), "<origin xyz=\"0 0 0.05\" rpy=\"0 -1.5707963267948966 0\"/>",
                                                        "<origin xyz=\"0 0.002 0.05\" rpy=\"0 -1.5707963267948966 0\"/>")),
              HasSubstr("the tool point is 2 mm off joint servo2's axis"));
  EXPECT_THAT(shape_error(make_xarm_kinematics, edited(urdf_text("xarm"), "<origin xyz=\"0 0 0.032\"", "<origin xyz=\"0 0.003 0.032\"")),
              HasSubstr("the tool point is 3 mm sideways of the base axis"));
}

TEST(KinematicShape, XarmAcceptsOtherLengths) {
  std::string text = edited(urdf_text("xarm"), "<origin xyz=\"0 0 0.09765\"", "<origin xyz=\"0 0 0.0988\"");
  text = edited(text, "<origin xyz=\"0 0 0.0965\"", "<origin xyz=\"0.001 0 0.0947\"");
  auto chain = read_urdf_chain(text, "base_link", "tool");
  ASSERT_TRUE(chain.ok());
  auto k = make_xarm_kinematics(*chain, urdf_position_limits(*chain));
  ASSERT_TRUE(k.ok()) << k.error().message;
  const JointVector q = joints({0.3, 0.3, 0.6, 0.3, 0.2});
  auto s = (*k)->inverse(IkRequest{(*k)->forward(q)}, q);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_reaches(**k, (*k)->forward(q), *s);
  EXPECT_TRUE(contains(*s, q));
}

TEST(KinematicShape, LimitsMustMatchTheChain) {
  const UrdfChain chain = testing::shipped_chain("scara");
  std::vector<PositionLimits> five(5, PositionLimits{-1, 1});
  auto k = make_scara_kinematics(chain, five);
  ASSERT_FALSE(k.ok());
  EXPECT_THAT(k.error().message, HasSubstr("5 limits given for the scara chain of 6 joints"));
  auto limits = urdf_position_limits(chain);
  limits[2] = {1, -1};
  auto inverted = make_scara_kinematics(chain, limits);
  ASSERT_FALSE(inverted.ok());
  EXPECT_THAT(inverted.error().message, HasSubstr("joint UAE: position limits"));
}

}  // namespace
}  // namespace armctl::motion

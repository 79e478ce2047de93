// The arm file's "link_lengths": applied to the URDF on load, so the loaded model's forward
// kinematics (and its link bodies) move by the length change; the fit's chain agrees with
// the loaded model; bad lengths are refused naming the key.
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "arm_files.hpp"
#include "calibration/calibration_chain.hpp"

namespace armctl::calibration {
namespace {

constexpr double kMm = 1e-3;

Eigen::Vector3d tool_point(const arm::ArmModel& m, const motion::JointVector& q) {
  const motion::Pose p = m.kinematics->forward(q);
  return p.position + p.orientation * m.tool.position;
}

TEST(LinkLengths, AStraightXarmGrowsByTheUpperArmsChange) {
  const arm::ArmModel nominal = arm::testing::shipped("xarm");
  auto doc = arm::testing::arm_json("xarm");
  doc["link_lengths"] = {{"servo4", "100mm"}};  // the URDF's 97.65 mm
  auto changed = arm::testing::parse("xarm", doc);
  ASSERT_TRUE(changed) << changed.error().message;
  // At zero the arm stands straight up: the tool point is 2.35 mm higher.
  const motion::JointVector zero = motion::JointVector::Zero(5);
  const Eigen::Vector3d d = tool_point(*changed, zero) - tool_point(nominal, zero);
  EXPECT_NEAR(d.z(), 2.35 * kMm, 1e-9);
  EXPECT_NEAR(d.head<2>().norm(), 0, 1e-9);
  // Bent at the shoulder by 90 deg the upper arm lies along x: the change is along x.
  motion::JointVector bent = zero;
  bent[1] = std::numbers::pi / 2;
  const Eigen::Vector3d e = tool_point(*changed, bent) - tool_point(nominal, bent);
  EXPECT_NEAR(e.x(), 2.35 * kMm, 1e-9);
  EXPECT_NEAR(e.z(), 0, 1e-9);
  ASSERT_EQ(changed->link_lengths.size(), 1u);
  EXPECT_EQ(changed->link_lengths[0].joint, "servo4");
  // The link bodies follow: the forearm's frame moves with the length.
  std::vector<Eigen::Isometry3d> a, b;
  const std::vector<double> q(6, 0.0);
  nominal.bodies->poses(q, a);
  changed->bodies->poses(q, b);
  const int forearm = *nominal.bodies->find("forearm");
  EXPECT_NEAR((b[std::size_t(forearm)].translation() - a[std::size_t(forearm)].translation()).z(), 2.35 * kMm, 1e-9);
  // And so does the URDF viewers get (the dashboard, ROS): the joint's origin is 100 mm long.
  EXPECT_EQ(nominal.urdf_text, arm::testing::urdf_text("xarm"));
  auto drawn = motion::read_urdf_chain(changed->urdf_text, "base_link", changed->tool_link);
  ASSERT_TRUE(drawn) << drawn.error().message;
  EXPECT_NEAR(drawn->joints[2].origin_xyz.norm(), 100 * kMm, 1e-12);
}

TEST(LinkLengths, TheFitsChainAgreesWithTheLoadedModelOnBothArms) {
  for (const char* arm : {"xarm", "scara"}) {
    SCOPED_TRACE(arm);
    const arm::ArmModel nominal = arm::testing::shipped(arm);
    auto chain = CalibrationChain::make(nominal);
    ASSERT_TRUE(chain) << chain.error().message;
    // Every length candidate changed by a few mm, through the file and through the chain.
    auto doc = arm::testing::arm_json(arm);
    std::vector<Parameter> ps;
    Eigen::VectorXd values(0);
    double delta = 1.3 * kMm;
    for (const Parameter& p : chain->candidates()) {
      if (p.kind != ParameterKind::length) continue;
      doc["link_lengths"][p.origin] = fmt::format("{:.9f}mm", (chain->length(p.origin) + delta) / kMm);
      ps.push_back(p);
      values.conservativeResize(values.size() + 1);
      values[values.size() - 1] = delta;
      delta = -delta * 1.7;
    }
    auto changed = arm::testing::parse(arm, doc);
    ASSERT_TRUE(changed) << changed.error().message;
    std::mt19937 random(5);
    for (int k = 0; k < 50; ++k) {
      motion::JointVector q(nominal.chain_joints());
      for (int i = 0; i < q.size(); ++i) {
        const auto& l = nominal.joints[std::size_t(i)].limits;
        q[i] = std::uniform_real_distribution<double>(l.lower, l.upper)(random);
      }
      const Eigen::Vector3d want = tool_point(*changed, q);
      EXPECT_NEAR((chain->tool_point(Eigen::VectorXd(q), ps, values) - want).norm(), 0, 1e-9);
      EXPECT_GT((tool_point(nominal, q) - want).norm(), 0.1 * kMm);  // the change shows
    }
  }
}

TEST(LinkLengths, BadLengthsAreRefusedNamingTheKey) {
  auto doc = arm::testing::arm_json("scara");
  doc["link_lengths"] = {{"SHOULDER", "10mm"}};  // its origin has no offset: no direction
  auto r = arm::testing::parse("scara", doc);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("link_lengths"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("SHOULDER"), std::string::npos) << r.error().message;
  doc["link_lengths"] = {{"elbow", "10mm"}};
  r = arm::testing::parse("scara", doc);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("elbow"), std::string::npos) << r.error().message;
  doc["link_lengths"] = {{"UAE", "-10mm"}};
  r = arm::testing::parse("scara", doc);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("UAE"), std::string::npos) << r.error().message;
  doc["link_lengths"] = {{"UAE", "10deg"}};
  r = arm::testing::parse("scara", doc);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("link_lengths.UAE"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace armctl::calibration

// The pictures of each joint's mark and positive direction (docs/calibration.md "Pictures"):
// the ones in the docs are what the shipped arm files draw today (a changed URDF or arm file
// that changes them fails here: `armctl calibrate --arm ARM --pictures docs/images/joints-ARM.svg`
// redraws them), one panel per joint, and an arm without link shapes gets a clear refusal.
#include <gtest/gtest.h>

#include <string>

#include "arm_files.hpp"
#include "calibration/joint_pictures.hpp"

namespace armctl::calibration {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

class JointPictures : public ::testing::TestWithParam<const char*> {};

TEST_P(JointPictures, TheDocsShowWhatTheShippedArmFileDraws) {
  const arm::ArmModel model = arm::testing::shipped(GetParam());
  auto svg = joint_pictures_svg(model);
  ASSERT_TRUE(svg.ok()) << svg.error().message;
  const std::string docs = std::string(ARMCTL_SOURCE_DIR) + "/docs/images/joints-" + GetParam() + ".svg";
  EXPECT_EQ(*svg, arm::testing::read_text(docs)) << docs << " is stale: redraw it with armctl calibrate --arm " << GetParam()
                                        << " --pictures " << docs;
}

TEST_P(JointPictures, OnePanelPerJointWithItsNameAndMark) {
  const arm::ArmModel model = arm::testing::shipped(GetParam());
  const std::string svg = joint_pictures_svg(model).value();
  EXPECT_EQ(count(svg, "grey: at its mark"), model.joints.size());
  for (int j = 0; j < model.joint_count(); ++j)
    EXPECT_NE(svg.find(">" + std::to_string(j + 1) + ". " + model.joints[std::size_t(j)].name + "<"), std::string::npos)
        << model.joints[std::size_t(j)].name;
  // Every revolute joint is seen along its axis, every prismatic one from the side.
  int turns = 0;
  for (const auto& j : model.joints) turns += j.dimension == Dimension::angle;
  EXPECT_EQ(count(svg, "positive turns this way"), std::size_t(turns));
  EXPECT_EQ(count(svg, "positive moves this way"), model.joints.size() - std::size_t(turns));
}

INSTANTIATE_TEST_SUITE_P(ShippedArms, JointPictures, ::testing::Values("xarm", "scara"));

TEST(JointPicturesRefused, AnArmWithoutLinkShapes) {
  arm::ArmModel model = arm::testing::shipped("xarm");
  model.bodies.reset();
  auto svg = joint_pictures_svg(model);
  ASSERT_FALSE(svg.ok());
  EXPECT_EQ(svg.error().kind, ErrorKind::invalid_config);
  EXPECT_NE(svg.error().message.find("no link shapes"), std::string::npos) << svg.error().message;
}

}  // namespace
}  // namespace armctl::calibration

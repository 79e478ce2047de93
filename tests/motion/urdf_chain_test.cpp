// The URDF chain reader on the shipped URDFs and on broken ones: each refusal names the
// element and what is allowed.
#include "motion/urdf_chain.hpp"
#include "motion/urdf_for_viewers.hpp"

#include <algorithm>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "arm_files.hpp"

namespace armctl::motion {
namespace {

using ::testing::HasSubstr;
using testing::edited;
using testing::urdf_text;

std::vector<std::string> names(const UrdfChain& c) {
  std::vector<std::string> out;
  for (const auto& j : c.joints) out.push_back(j.name);
  return out;
}

TEST(UrdfChain, ScaraChainIsZThenFiveRevoluteJoints) {
  const UrdfChain c = testing::shipped_chain("scara");
  EXPECT_EQ(c.robot_name, "scara");
  EXPECT_THAT(names(c), ::testing::ElementsAre("Z", "SHOULDER", "UAE", "UAJ", "SKE", "SKF"));
  EXPECT_EQ(c.joints[0].type, ChainJointType::prismatic);
  for (std::size_t i = 1; i < 6; ++i) EXPECT_EQ(c.joints[i].type, ChainJointType::revolute) << i;
  EXPECT_DOUBLE_EQ(c.joints[0].limits.lower, 0.0);
  EXPECT_DOUBLE_EQ(c.joints[0].limits.upper, 0.3);
  EXPECT_NEAR(c.joints[2].origin_xyz.x(), 0.255, 1e-15);
  EXPECT_NEAR(c.joints[3].origin_xyz.x(), 0.255, 1e-15);
  EXPECT_NEAR(c.joints[4].origin_rpy.x(), M_PI / 2, 1e-15);
  EXPECT_NEAR((c.tip_from_last.translation() - Eigen::Vector3d(0.175, 0, 0)).norm(), 0, 1e-15);
  EXPECT_THAT(c.fixed_joints, ::testing::ElementsAre("tool_point"));
  // The same fixed joint with its own origin, after the last moving joint.
  ASSERT_EQ(c.fixed.size(), 1u);
  EXPECT_EQ(c.fixed[0].name, "tool_point");
  EXPECT_EQ(c.fixed[0].before, c.joints.size());
  EXPECT_NEAR((c.fixed[0].origin.translation() - Eigen::Vector3d(0.175, 0, 0)).norm(), 0, 1e-15);
}

TEST(UrdfChain, OriginLengthsReplaceTheOffsetsKeepingTheirDirection) {
  const std::string urdf = testing::urdf_text("scara");
  const std::vector<OriginLength> lengths{{"UAE", 0.26}, {"tool_point", 0.18}};
  auto c = read_urdf_chain(urdf, "base_link", "tool", lengths);
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_NEAR((c->joints[2].origin_xyz - Eigen::Vector3d(0.26, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((c->joints[2].from_previous.translation() - Eigen::Vector3d(0.26, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((c->tip_from_last.translation() - Eigen::Vector3d(0.18, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR(c->joints[3].origin_xyz.x(), 0.255, 1e-15);  // not named: as the URDF has it
  for (const std::vector<OriginLength>& bad :
       {std::vector<OriginLength>{{"SHOULDER", 0.1}}, std::vector<OriginLength>{{"nope", 0.1}},
        std::vector<OriginLength>{{"UAE", 0.0}}, std::vector<OriginLength>{{"UAE", 0.2}, {"UAE", 0.3}}}) {
    auto r = read_urdf_chain(urdf, "base_link", "tool", bad);
    ASSERT_FALSE(r) << bad[0].joint;
    EXPECT_NE(r.error().message.find(bad[0].joint), std::string::npos) << r.error().message;
  }
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The URDF text a viewer gets with calibrated lengths: read back without lengths it is the
// chain read with them, and nothing else of the file is lost.
TEST(UrdfChain, LengthsWrittenIntoTheTextGiveTheChainReadWithThem) {
  const std::string urdf = testing::urdf_text("scara");
  const std::vector<OriginLength> lengths{{"UAE", 0.26}, {"tool_point", 0.18}};
  auto text = urdf_for_viewers(urdf, lengths);
  ASSERT_TRUE(text) << text.error().message;
  auto want = read_urdf_chain(urdf, "base_link", "tool", lengths);
  auto got = read_urdf_chain(*text, "base_link", "tool");
  ASSERT_TRUE(want && got);
  ASSERT_EQ(got->joints.size(), want->joints.size());
  for (std::size_t i = 0; i < got->joints.size(); ++i)
    EXPECT_TRUE(got->joints[i].from_previous.isApprox(want->joints[i].from_previous, 1e-12)) << i;
  EXPECT_TRUE(got->tip_from_last.isApprox(want->tip_from_last, 1e-12));
  EXPECT_NEAR(got->joints[2].origin_xyz.x(), 0.26, 1e-12);
  // Visuals, collisions and comments are kept.
  for (const char* element : {"<visual", "<collision", "<!--", "<material", "<limit"})
    EXPECT_EQ(count(*text, element), count(urdf, element)) << element;
  // No lengths: the text as written; a bad one: refused naming the joint.
  auto same = urdf_for_viewers(urdf, {});
  ASSERT_TRUE(same);
  EXPECT_EQ(*same, urdf);
  for (const std::vector<OriginLength>& bad :
       {std::vector<OriginLength>{{"SHOULDER", 0.1}}, std::vector<OriginLength>{{"nope", 0.1}},
        std::vector<OriginLength>{{"UAE", -1.0}}}) {
    auto r = urdf_for_viewers(urdf, bad);
    ASSERT_FALSE(r) << bad[0].joint;
    EXPECT_THAT(r.error().message, HasSubstr(bad[0].joint));
  }
  EXPECT_FALSE(urdf_for_viewers("<robot", lengths));
}

TEST(UrdfChain, XarmChainIsFiveServosBaseToWrist) {
  const UrdfChain c = testing::shipped_chain("xarm");
  EXPECT_THAT(names(c), ::testing::ElementsAre("servo6", "servo5", "servo4", "servo3", "servo2"));
  for (const auto& j : c.joints) {
    EXPECT_EQ(j.type, ChainJointType::revolute);
    EXPECT_NEAR(j.limits.lower, -2 * M_PI / 3, 1e-15);
    EXPECT_NEAR(j.limits.upper, 2 * M_PI / 3, 1e-15);
  }
  EXPECT_NEAR(c.joints[2].origin_xyz.z(), 0.09765, 1e-15);
}

TEST(UrdfChain, TheGripperIsNotInTheChainButCanBeItsOwn) {
  auto g = read_urdf_chain(urdf_text("scara"), "wrist_roll", "gripper_finger");
  ASSERT_TRUE(g.ok()) << g.error().message;
  ASSERT_EQ(g->joints.size(), 1u);
  EXPECT_EQ(g->joints[0].name, "SKG");
  EXPECT_EQ(g->joints[0].type, ChainJointType::prismatic);
}

TEST(UrdfChain, AxisIsNormalised) {
  auto c = read_urdf_chain(edited(urdf_text("xarm"), "<axis xyz=\"0 1 0\"/>", "<axis xyz=\"0 3 0\"/>"), "base_link",
                           "tool");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_NEAR((c->joints[1].axis - Eigen::Vector3d::UnitY()).norm(), 0, 1e-15);
}

void expect_refused(const std::string& text, const std::string& base, const std::string& tip,
                    const std::vector<std::string>& parts) {
  auto c = read_urdf_chain(text, base, tip);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error().kind, ErrorKind::invalid_config);
  for (const auto& p : parts) EXPECT_THAT(c.error().message, HasSubstr(p));
}

TEST(UrdfChain, RefusesWhatIsNotUrdf) {
  expect_refused("", "base_link", "tool", {"URDF not accepted"});
  expect_refused("<robot", "base_link", "tool", {"URDF not accepted"});
  expect_refused("<notarobot name=\"x\"/>", "base_link", "tool", {"URDF not accepted"});
}

TEST(UrdfChain, RefusesTextThatIsNotUtf8) {
  // A cut-short UTF-8 character at the end made urdfdom's XML parser read past the text.
  std::string text = urdf_text("xarm");
  expect_refused(text + "\xC3", "base_link", "tool", {"byte " + std::to_string(text.size()) + " is not UTF-8"});
  expect_refused(edited(text, "xArm", "x\xFFrm"), "base_link", "tool", {"is not UTF-8"});
  expect_refused(edited(text, "xArm", "x\xED\xA0\x80rm"), "base_link", "tool", {"is not UTF-8"});  // a surrogate
  expect_refused(edited(text, "xArm", std::string("x\0rm", 4)), "base_link", "tool", {"is not UTF-8"});
  // Real UTF-8 is fine.
  EXPECT_TRUE(read_urdf_chain(edited(text, "xArm", "x\xC3\xA4rm \xE2\x80\x94 \xF0\x9F\xA4\x96"), "base_link", "tool").ok());
}

// urdfdom logs a number it cannot read with that text as the printf format: rpy="0 1%n 0"
// made it write through a pointer it never had (found by fuzz_urdf_chain). A '%' outside a
// comment never reaches it; in a comment it is fine (and never logged).
TEST(UrdfChain, RefusesAPercentSignOutsideComments) {
  const std::string text = urdf_text("xarm");
  const std::string bad = edited(text, "<origin xyz=\"0 0 0.05\" rpy=\"0 -1.5707963267948966 0\"/>",
                                 "<origin xyz=\"0 0 0.05\" rpy=\"0 -1.57r%111111n 0\"/>");
  ASSERT_NE(bad, text);
  const auto line = 1 + std::count(bad.begin(), bad.begin() + bad.find('%'), '\n');
  expect_refused(bad, "base_link", "tool", {"a '%' at line " + std::to_string(line) + ", column ", "<!-- comments -->"});
  expect_refused(edited(text, "name=\"servo2\"", "name=\"servo%s\""), "base_link", "tool", {"a '%' at line"});
  auto c = read_urdf_chain(edited(text, "<robot name=\"xarm\">", "<!-- 100 % kinematics --><robot name=\"xarm\">"),
                           "base_link", "tool");
  EXPECT_TRUE(c.ok()) << c.error().message;
  // A "<!--" inside a tag is no comment to the XML parser, though a simple scan takes it for
  // one: the '%' after it must still never reach urdfdom (fuzz_urdf_chain found this; it crashed).
  const std::string inside_a_tag =
      edited(edited(text, "<joint name=\"tool_point\" type=\"fixed\">", "<joint name=\"tool_point\" type=<ro<!-->"),
             "rpy=\"0 -1.5707963267948966 0\"/>", "rpy=\"0 -1.57r%111111n 0\"/>");
  ASSERT_NE(inside_a_tag.find("<ro<!-->"), std::string::npos);
  ASSERT_NE(inside_a_tag.find('%'), std::string::npos);
  EXPECT_FALSE(read_urdf_chain(inside_a_tag, "base_link", "tool").ok());  // refused, not a crash
}

TEST(UrdfChain, RefusesMissingLinks) {
  expect_refused(urdf_text("scara"), "floor", "tool", {"no <link name=\"floor\">", "base link"});
  expect_refused(urdf_text("scara"), "base_link", "hand", {"no <link name=\"hand\">", "tip link"});
}

TEST(UrdfChain, RefusesATipNotBelowTheBase) {
  expect_refused(urdf_text("scara"), "tool", "base_link", {"link 'base_link' is not below link 'tool'"});
  expect_refused(urdf_text("scara"), "gripper_finger", "tool", {"not below"});
}

TEST(UrdfChain, RefusesContinuousAndFloatingJointsInTheChain) {
  const std::string continuous = edited(urdf_text("scara"), "name=\"UAE\" type=\"revolute\"", "name=\"UAE\" type=\"continuous\"");
  expect_refused(continuous, "base_link", "tool", {"joint 'UAE' is continuous", "revolute (with limits), prismatic or fixed"});
  const std::string floating = edited(urdf_text("scara"), "name=\"tool_point\" type=\"fixed\"", "name=\"tool_point\" type=\"floating\"");
  expect_refused(floating, "base_link", "tool", {"joint 'tool_point' is floating"});
  // Outside the chain anything URDF allows is fine.
  const std::string gripper = edited(urdf_text("scara"), "name=\"SKG\" type=\"prismatic\"", "name=\"SKG\" type=\"continuous\"");
  EXPECT_TRUE(read_urdf_chain(gripper, "base_link", "tool").ok());
}

TEST(UrdfChain, RefusesAZeroAxis) {
  expect_refused(edited(urdf_text("xarm"), "<axis xyz=\"0 1 0\"/>", "<axis xyz=\"0 0 0\"/>"), "base_link", "tool",
                 {"joint 'servo5'", "<axis> xyz is zero"});
}

TEST(UrdfChain, RefusesEmptyOrInvertedLimits) {
  expect_refused(edited(urdf_text("scara"), "lower=\"0\" upper=\"0.3\"", "lower=\"0.3\" upper=\"0\""), "base_link", "tool",
                 {"joint 'Z'", "lower < upper"});
}

TEST(UrdfChain, RefusesARevoluteJointWithoutLimits) {
  const std::string text = edited(urdf_text("xarm"),
                                  "<limit lower=\"-2.0943951023931953\" upper=\"2.0943951023931953\" effort=\"2\" velocity=\"5\"/>",
                                  "");
  auto c = read_urdf_chain(text, "base_link", "tool");
  ASSERT_FALSE(c.ok());
  EXPECT_THAT(c.error().message, HasSubstr("servo6"));
}

TEST(UrdfChain, RefusesMimicJointsInTheChain) {
  const std::string text = edited(urdf_text("scara"), "<joint name=\"UAJ\" type=\"revolute\">",
                                  "<joint name=\"UAJ\" type=\"revolute\">\n    <mimic joint=\"UAE\"/>");
  expect_refused(text, "base_link", "tool", {"joint 'UAJ' has <mimic>"});
}

TEST(UrdfChain, RefusesNonFiniteOrigins) {
  const std::string text = edited(urdf_text("scara"), "<origin xyz=\"0.255 0 0\"", "<origin xyz=\"nan 0 0\"");
  auto c = read_urdf_chain(text, "base_link", "tool");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error().kind, ErrorKind::invalid_config);
}

TEST(UrdfChain, FileErrorsNameTheFile) {
  auto missing = read_urdf_chain_file("/nonexistent/arm.urdf", "base_link", "tool");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().kind, ErrorKind::io);
  EXPECT_THAT(missing.error().message, HasSubstr("/nonexistent/arm.urdf"));
  auto wrong_tip = read_urdf_chain_file(testing::urdf_path("xarm"), "base_link", "nowhere");
  ASSERT_FALSE(wrong_tip.ok());
  EXPECT_THAT(wrong_tip.error().message, HasSubstr("xarm.urdf: "));
}

}  // namespace
}  // namespace armctl::motion

namespace armctl::motion {
namespace {

// Found by fuzz_urdf_chain: urdfdom accepts a joint with name="".
TEST(UrdfChain, AJointWithoutANameIsRefused) {
  const std::string urdf =
      "<robot name=\"r\"><link name=\"base_link\"/><link name=\"tool\"/>"
      "<joint name=\"\" type=\"revolute\"><parent link=\"base_link\"/><child link=\"tool\"/>"
      "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint></robot>";
  auto c = read_urdf_chain(urdf, "base_link", "tool");
  ASSERT_FALSE(c.ok());
  EXPECT_THAT(c.error().message, ::testing::HasSubstr("empty name"));
}

}  // namespace
}  // namespace armctl::motion

// Arm files: the shipped ones load and agree with their URDFs; every kind of bad file is
// refused with an error that names the key or URDF element and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "arm_files.hpp"

namespace armctl::arm {
namespace {

using testing::arm_json;
using testing::parse;
using testing::shipped;
constexpr double kDeg = std::numbers::pi / 180;

TEST(ArmModel, ShippedArmsLoad) {
  ArmModel x = shipped("xarm");
  EXPECT_EQ(x.name, "xarm");
  EXPECT_EQ(x.chain_joints(), 5);
  ASSERT_EQ(x.joint_count(), 6);
  EXPECT_EQ(x.joints[0].name, "servo6");  // base yaw first
  EXPECT_EQ(x.joints[5].role, JointRole::gripper);
  ASSERT_TRUE(x.gripper);
  EXPECT_TRUE(x.supports(Protocol::robot_commands));
  EXPECT_FALSE(x.supports(Protocol::joint_bus));

  ArmModel s = shipped("scara");
  EXPECT_EQ(s.chain_joints(), 6);
  ASSERT_EQ(s.joint_count(), 7);
  EXPECT_EQ(s.joints[0].dimension, Dimension::length);  // Z
  EXPECT_EQ(s.joints[6].name, "SKG");
  EXPECT_TRUE(s.supports(Protocol::robot_commands));
  EXPECT_TRUE(s.supports(Protocol::joint_bus));
  ASSERT_EQ(s.couplings.size(), 1u);
}

TEST(ArmModel, XarmServoUnitsAre240DegreesOver1000) {
  ArmModel x = shipped("xarm");
  std::vector<double> q(6, 0.0);
  for (double d : x.to_device(Protocol::robot_commands, q)) EXPECT_NEAR(d, 500, 1e-9);
  q[0] = 120 * kDeg;
  EXPECT_NEAR(x.to_device(Protocol::robot_commands, q)[0], 1000, 1e-9);
  q[0] = -24 * kDeg;
  EXPECT_NEAR(x.to_device(Protocol::robot_commands, q)[0], 400, 1e-9);
}

TEST(ArmModel, ScaraClicksAndTheDifferentialWrist) {
  ArmModel s = shipped("scara");
  std::vector<double> q(7, 0.0);
  q[1] = 2 * std::numbers::pi;  // one turn of SHOULDER
  EXPECT_NEAR(s.to_device(Protocol::joint_bus, q)[1], 10115.702, 1e-3);
  // SKE alone turns both wrist motors the same way; SKF alone turns them opposite ways.
  q.assign(7, 0.0);
  q[4] = 10 * kDeg;
  auto d = s.to_device(Protocol::joint_bus, q);
  EXPECT_NEAR(d[4], d[5], 1e-9);
  EXPECT_GT(d[4], 0);
  q.assign(7, 0.0);
  q[5] = 10 * kDeg;
  d = s.to_device(Protocol::joint_bus, q);
  EXPECT_NEAR(d[4], -d[5], 1e-9);
  // Round trip through both protocols.
  const std::vector<double> any{0.12, 0.3, -0.7, 1.1, -0.4, 0.9, 0.02};
  for (Protocol p : {Protocol::joint_bus, Protocol::robot_commands}) {
    const auto back = s.from_device(p, s.to_device(p, any));
    for (std::size_t i = 0; i < any.size(); ++i) EXPECT_NEAR(back[i], any[i], 1e-12) << to_string(p) << " " << i;
  }
}

// Each edit of the shipped xArm file, and a part of the error it must produce.
struct BadEdit {
  const char* what;
  void (*edit)(nlohmann::json&);
  const char* message;
};

TEST(ArmModel, BadFilesAreRefusedNamingTheProblem) {
  const BadEdit cases[] = {
      {"unknown key", [](nlohmann::json& j) { j["colour"] = "red"; }, "colour: unknown key"},
      {"unknown family", [](nlohmann::json& j) { j["family"] = "delta"; }, "unknown arm family 'delta' (known: xarm, scara"},
      {"joint not in URDF", [](nlohmann::json& j) { j["joints"][1]["name"] = "elbow"; }, "has no joint named 'elbow'"},
      {"chain joint missing", [](nlohmann::json& j) { j["joints"].erase(1); }, "which the arm file does not describe"},
      {"wrong unit for the joint type",
       [](nlohmann::json& j) { j["joints"][0]["limits"]["position"][0] = "-100mm"; },
       "joints[0].limits.position[0]"},
      {"limits beyond the URDF",
       [](nlohmann::json& j) { j["joints"][0]["limits"]["position"][1] = "150deg"; }, "beyond the URDF's limits"},
      {"inverted limits",
       [](nlohmann::json& j) { j["joints"][0]["limits"]["position"] = {"10deg", "-10deg"}; }, "must be below upper"},
      {"zero velocity", [](nlohmann::json& j) { j["joints"][2]["limits"]["velocity"] = "0deg/s"; }, "must be above zero"},
      {"NaN-like text", [](nlohmann::json& j) { j["joints"][2]["limits"]["velocity"] = "nandeg/s"; }, "velocity"},
      {"servo out of range", [](nlohmann::json& j) { j["joints"][0]["robot_commands"]["servo"] = 40; }, "servo"},
      {"device beyond 0..1000",
       [](nlohmann::json& j) { j["joints"][0]["robot_commands"]["device"] = {0, 1200}; }, "outside the allowed range"},
      {"servo used twice", [](nlohmann::json& j) { j["joints"][1]["robot_commands"]["servo"] = 6; }, "used twice"},
      {"no mapping", [](nlohmann::json& j) { j["joints"][1].erase("robot_commands"); }, "needs a device mapping"},
      {"gripper on the chain", [](nlohmann::json& j) { j["gripper"]["joint"] = "servo3"; }, "not a gripper"},
      {"gripper outside limits", [](nlohmann::json& j) { j["gripper"]["closed"] = "130deg"; }, "inside the gripper joint's"},
      {"singular coupling",
       [](nlohmann::json& j) {
         j["couplings"] = nlohmann::json::array({{{"joints", {"servo3", "servo2"}}, {"matrix", {{1, 1}, {2, 2}}}}});
       },
       "singular"},
      {"tool frame without units", [](nlohmann::json& j) { j["tool_frame"] = {{"xyz", {0, 0, 0}}}; }, "tool_frame.xyz[0]"},
      {"not an object", [](nlohmann::json& j) { j = nlohmann::json::array(); }, "must be an object"},
  };
  for (const auto& c : cases) {
    nlohmann::json doc = arm_json("xarm");
    c.edit(doc);
    auto r = parse("xarm", doc);
    ASSERT_FALSE(r) << c.what;
    EXPECT_EQ(r.error().kind, ErrorKind::invalid_config) << c.what;
    EXPECT_NE(r.error().message.find(c.message), std::string::npos) << c.what << ": " << r.error().message;
  }
}

TEST(ArmModel, UrdfThatDisagreesIsRefused) {
  const nlohmann::json doc = arm_json("scara");
  std::string urdf = testing::urdf_text("scara");
  // Z made revolute in the URDF: the arm file's millimetres no longer fit.
  const auto at = urdf.find("name=\"Z\" type=\"prismatic\"");
  ASSERT_NE(at, std::string::npos);
  urdf.replace(at, std::string("name=\"Z\" type=\"prismatic\"").size(), "name=\"Z\" type=\"revolute\"");
  auto r = parse_arm_model(doc.dump(), "scara.arm.json", urdf, "scara.urdf");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("joints[0].limits.position[0]"), std::string::npos) << r.error().message;
  auto broken = parse_arm_model(doc.dump(), "scara.arm.json", "<robot name='x'>", "scara.urdf");
  ASSERT_FALSE(broken);
  EXPECT_NE(broken.error().message.find("scara.urdf"), std::string::npos) << broken.error().message;
}

TEST(ArmModel, FilesThatAreNotFilesAreRefused) {
  auto missing = load_arm_model("/nonexistent/arm.json");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("no such file"), std::string::npos);
  auto dir = load_arm_model(ARMCTL_SOURCE_DIR);
  ASSERT_FALSE(dir);
  EXPECT_NE(dir.error().message.find("not a regular file"), std::string::npos);
}

}  // namespace
}  // namespace armctl::arm

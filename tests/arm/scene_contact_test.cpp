// The simulators know the scene; the host does not: a move into a box only the simulator has
// (the host plans it: its scene is empty) stops at contact — the xArm emulator's servos and
// the SCARA's simulated joints stall against the box — and the host's stall protection stops
// the arm, releases the joint and names it. On simulated time, on both arms.
#include <gtest/gtest.h>

#include "arm/arm.hpp"
#include "arm/arm_kinematics.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm/scene_obstacle.hpp"
#include "arm_files.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::arm {
namespace {

scene::Scene scene_of(const std::string& json) { return scene::parse_scene(json, "scene").value(); }

// How deep the arm is in the scene at `joints` (m; 0: clear): the world the simulator meets.
double depth(const ArmModel& model, const scene::Scene& scene, const std::vector<double>& joints) {
  const auto c = scene_only_world(model, scene).value()->contact(joints);
  return c ? c->depth : 0.0;
}

TEST(SceneContact, TheXarmEmulatorsServosStallAtTheBoxAndTheHostNamesTheJoint) {
  const ArmModel model = testing::shipped("xarm");
  // examples/scenes/xarm-desk.json's box, without the desk.
  const scene::Scene scene = scene_of(R"({"objects": [{"name": "box", "box": [50, 50, 80], "at": [150, -100, 40]}]})");
  xarm::XarmEmulatorOptions options;
  options.touches = scene_obstacle(model, Protocol::robot_commands, scene).value();
  robot_commands::testing::EmulatedLink link{9600, std::move(options)};
  robot_commands::Client client{link};
  Arm arm{model, std::make_unique<RcArmDevice>(model, client)};
  // Into the box (with the scene the planner refuses this: SceneCli); the host has no scene.
  CartesianGoal into;
  into.position = Eigen::Vector3d(0.150, -0.100, 0.060);
  ASSERT_TRUE(arm.move_to(into));
  auto w = arm.wait();
  ASSERT_FALSE(w) << "the arm went into the box";
  const JointStall* s = stall_of(w.error());
  ASSERT_NE(s, nullptr) << w.error().message;
  EXPECT_FALSE(s->name.empty());
  EXPECT_GE(s->seconds, 0.5);
  EXPECT_NE(w.error().message.find("joint " + s->name + " stalled"), std::string::npos) << w.error().message;
  // Stopped at the box (within a servo unit's rounding of it), short of the target; the
  // stalled servo limp.
  const auto at = arm.read().value().positions;
  EXPECT_LT(depth(model, scene, at), 0.002);
  EXPECT_GT((arm.forward(arm.chain_of(at)).position - into.position).norm(), 0.005);
  const int servo = model.joints[std::size_t(s->joint)].map(Protocol::robot_commands)->id;
  EXPECT_FALSE(link.emulator().servos().torque(rc_board::ServoId(servo)));
  // Away from the box the arm moves again.
  CartesianGoal up;
  up.position = Eigen::Vector3d(0.150, 0.0, 0.200);
  ASSERT_TRUE(arm.move_to(up));
  auto back = arm.wait();
  EXPECT_TRUE(back) << back.error().message;
}

TEST(SceneContact, TheScarasSimulatedJointStallsOnTheBoxAndTheHostNamesIt) {
  const ArmModel model = testing::shipped("scara");
  // Under the stretched-out arm's tool, its top at 260 mm (PlanCollisions' box; the example
  // of docs/scene.md "Simulators").
  const scene::Scene scene =
      scene::load_scene(std::string(ARMCTL_SOURCE_DIR) + "/examples/scenes/scara-box.json").value();
  auto sim = test::make_arm(115200);
  sim->set_obstacle(scene_obstacle(model, Protocol::joint_bus, scene).value());
  joint_bus::BusMaster master{sim->link()};
  Arm arm{model, std::make_unique<BusArmDevice>(model, master, sim->link(), "simulated SCARA")};
  // Up above the box (the tool 300 mm up, its fingers 15 mm lower), then straight down 50 mm
  // into it (a board move of 3.2 s at Z's speed: the stall is seen once its time is up).
  std::vector<std::optional<double>> z(std::size_t(model.joint_count()));
  z[0] = 0.10;
  ASSERT_TRUE(arm.move_joints(z));
  ASSERT_TRUE(arm.wait());
  z[0] = 0.05;
  ASSERT_TRUE(arm.move_joints(z));
  auto w = arm.wait();
  ASSERT_FALSE(w) << "the arm went into the box";
  const JointStall* s = stall_of(w.error());
  ASSERT_NE(s, nullptr) << w.error().message << " at Z " << arm.read().value().positions[0];
  EXPECT_EQ(s->name, "Z");
  EXPECT_GE(s->seconds, 0.5);
  // Held at the box's top (its fingers at 260 mm: Z at 75 mm), the Z joint's loop off.
  const auto at = arm.read().value().positions;
  EXPECT_LT(depth(model, scene, at), 0.002);
  EXPECT_NEAR(at[0], 0.075, 0.005);
  EXPECT_FALSE(sim->joint(1).controller().loop_enabled());
  // Up again, away from it, the joint follows.
  z[0] = 0.10;
  ASSERT_TRUE(arm.set_torque(true));
  ASSERT_TRUE(arm.move_joints(z));
  auto back = arm.wait();
  EXPECT_TRUE(back) << back.error().message;
}

}  // namespace
}  // namespace armctl::arm

// The Arm API on the SCARA through the Mega controller on emulated silicon (mega_rig.hpp):
// arm::Arm over RcArmDevice over the Robot Commands SDK, as `armctl arm --device
// serial:/dev/ttyACM0` drives the real board. Judged by the joints' emulated encoders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <set>
#include <vector>

#include "arm/arm.hpp"
#include "arm/motion_executor.hpp"
#include "arm/motion_planning.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm_files.hpp"
#include "mega_rig.hpp"

namespace armctl::hil {
namespace {

using namespace std::chrono_literals;
using arm::Arm;
using arm::Protocol;
using arm::RcArmDevice;

struct MegaArm {
  explicit MegaArm(std::uint32_t baud = 9600, const std::set<int>& leads_swapped = {})
      : rig(baud, leads_swapped),
        model(arm::testing::shipped("scara")),
        arm(model, std::make_unique<RcArmDevice>(model, *rig.client)) {}
  // Where the joints truly are (emulated encoders), in SI through the arm file's joint-bus map.
  std::vector<double> true_positions() {
    std::vector<double> device;
    for (const auto& j : model.joints) device.push_back(rig.clicks(j.map(Protocol::joint_bus)->id));
    return model.from_device(Protocol::joint_bus, device);
  }
  MegaRig rig;
  arm::ArmModel model;
  Arm arm;
};

TEST(MegaArm, PtpMoveArrivesWhereTheArmApiAsked) {
  MegaArm m;
  const std::vector<std::optional<double>> targets{0.15, 0.3, -0.8, 0.2, 0.0, 0.0, std::nullopt};
  auto moved = m.arm.move_joints(targets);
  ASSERT_TRUE(moved) << moved.error().message;
  auto w = m.arm.wait();
  ASSERT_TRUE(w) << w.error().message;
  const auto truth = m.true_positions();
  // The resolution through the controller: one Robot Commands unit of each joint.
  auto device = m.model.to_device(Protocol::robot_commands, truth);
  for (double& d : device) d += 1.0;
  const auto one_unit_on = m.model.from_device(Protocol::robot_commands, device);
  for (std::size_t i = 0; i < 6; ++i) {
    const double unit = std::abs(one_unit_on[i] - truth[i]);
    EXPECT_NEAR(truth[i], *targets[i], 2 * unit) << m.model.joints[i].name << " (one unit " << unit << ")";
  }
}

TEST(MegaArm, StopHaltsTheArmShortOfItsTarget) {
  MegaArm m;
  ASSERT_TRUE(m.arm.move_joints({0.1, 1.2, -1.2, 0.0, 0.0, 0.0, std::nullopt}, arm::MoveOptions{}));
  m.rig.mega.advance(600ms);
  ASSERT_TRUE(m.arm.stop());
  m.rig.mega.advance(800ms);
  const auto held = m.true_positions();
  m.rig.mega.advance(1000ms);
  const auto later = m.true_positions();
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(later[i], held[i], 0.005) << m.model.joints[i].name << " at rest";
  EXPECT_LT(held[1], 1.1) << "SHOULDER stopped short of 1.2 rad";
  EXPECT_GT(held[1], 0.05) << "SHOULDER had started";
}

// What the dashboard and ROS show (ArmDevice::health, read by the session's status poll):
// the battery, and each servo's faults that JointFaultRead answers. UAE (servo 3) has its
// motor leads swapped: driven, it runs away and stops itself with a runaway fault.
TEST(MegaArm, HealthReportsTheJointFaultsTheMegaFound) {
  MegaArm m(115200, {3});
  const auto before = m.arm.device().health();
  ASSERT_TRUE(before.battery_volts.has_value());
  EXPECT_NEAR(*before.battery_volts, 24.0, 1e-9);
  EXPECT_TRUE(before.faults.empty()) << before.faults.front();
  ASSERT_TRUE(m.arm.move_joints({std::nullopt, 0.3, -0.8, std::nullopt, std::nullopt, std::nullopt, std::nullopt},
                                arm::MoveOptions{}));
  m.rig.mega.advance(2500ms);
  const auto after = m.arm.device().health();
  ASSERT_EQ(after.faults.size(), 1u);
  // Which check of the Mega's finds it first (behind its ramp, or out of its move's stretch)
  // turns on microseconds of bus timing; either way the move stops.
  EXPECT_EQ(after.faults[0].rfind("servo 3: runaway (bridge off until clear-faults)", 0), 0u) << after.faults[0];
  EXPECT_LT(m.true_positions()[1], 0.25) << "SHOULDER's move (to 0.3 rad) was stopped with UAE's";
  EXPECT_EQ(m.rig.client->has_joint_faults(), true);

  // Cleared (JointFaultClear, CMD 41, through the Mega to each joint): no fault left, and
  // UAE drives again. Its leads are still swapped (the cause not fixed), so driven it runs
  // away once more: it moves, where a joint still holding its fault refuses the drive and
  // stays put.
  auto cleared = m.arm.device().clear_faults();
  ASSERT_TRUE(cleared) << cleared.error().message;
  const auto now = m.arm.device().health();
  EXPECT_TRUE(now.faults.empty()) << now.faults.front();
  const int uae_before = m.rig.clicks(3);
  ASSERT_TRUE(m.arm.move_joints({std::nullopt, std::nullopt, 0.0, std::nullopt, std::nullopt, std::nullopt,
                                 std::nullopt},
                                arm::MoveOptions{}));
  m.rig.mega.advance(2500ms);
  EXPECT_GT(std::abs(m.rig.clicks(3) - uae_before), 500) << "UAE was driven again after the clear";
  const auto again = m.arm.device().health();
  ASSERT_EQ(again.faults.size(), 1u);
  EXPECT_EQ(again.faults[0].rfind("servo 3: runaway", 0), 0u) << again.faults[0];
}

}  // namespace
}  // namespace armctl::hil

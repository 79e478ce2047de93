// The simulated SCARA mis-assembled on purpose (core/miscalibration.hpp): the joints count
// from where they were homed and one turns the other way, which only the physical arm
// (true_position) shows; the end stops stay where they are physically.
#include <gtest/gtest.h>

#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_sim/sim_arm.hpp"

namespace armctl::joint_sim {
namespace {

std::unique_ptr<SimArm> make(std::optional<Miscalibration> miscal) {
  SimArmOptions o;
  o.miscal = std::move(miscal);
  return std::make_unique<SimArm>(load_arm_config(default_arm_config_path()), o);
}

// Torque off (position loops off) on every joint, as a user does before moving the arm by hand.
void limp(SimArm& arm) {
  joint_bus::BusMaster master(arm.link());
  for (int j = 1; j <= 7; ++j) ASSERT_TRUE(master.set_pid_state(j, false)) << j;
}

TEST(ScaraMiscal, WithoutMiscalTheTruthIsTheEncoder) {
  auto arm = make(std::nullopt);
  EXPECT_FALSE(arm->move_by_hand_to(2, 500));  // the loop holds it
  limp(*arm);
  ASSERT_TRUE(arm->joint(2).turn_by_hand(500));
  EXPECT_DOUBLE_EQ(arm->true_position(2), 500);
  EXPECT_DOUBLE_EQ(arm->true_position(2), arm->joint(2).hardware().position_clicks());
  EXPECT_FALSE(arm->miscalibration().has_value());
}

TEST(ScaraMiscal, EveryJointStartsAtItsShiftAndTheFlippedOneTurnsBack) {
  const Miscalibration m = make_miscalibration(MiscalArm::scara, 7);
  auto arm = make(m);
  limp(*arm);
  int flipped = 0;
  for (int j = 1; j <= 7; ++j) {
    EXPECT_EQ(arm->joint(j).hardware().encoder_count(), 0) << j;
    EXPECT_DOUBLE_EQ(arm->true_position(j), m.joint(j).zero_shift) << j;
    ASSERT_TRUE(arm->joint(j).turn_by_hand(300)) << j;  // the encoder counts 300 on
    EXPECT_DOUBLE_EQ(arm->true_position(j), m.joint(j).zero_shift + (m.joint(j).flipped ? -300 : 300)) << j;
    flipped += m.joint(j).flipped;
  }
  EXPECT_EQ(flipped, 1);
}

TEST(ScaraMiscal, AHandMovesALimpJointToATruePosition) {
  const Miscalibration m = make_miscalibration(MiscalArm::scara, 11);
  auto arm = make(m);
  limp(*arm);
  for (int j = 1; j <= 7; ++j) {
    ASSERT_TRUE(arm->move_by_hand_to(j, 1000)) << j;
    EXPECT_NEAR(arm->true_position(j), 1000, 1e-9) << j;
    EXPECT_NEAR(arm->joint(j).hardware().position_clicks(), m.device_position(j, 1000), 1e-9) << j;
  }
}

TEST(ScaraMiscal, TheEndStopsStayWhereTheyArePhysically) {
  const Miscalibration m = make_miscalibration(MiscalArm::scara, 7);
  auto plain = make(std::nullopt);
  auto arm = make(m);
  for (int j : {1, 2, 3, 7}) {  // the joints with end stops in config/scara.arm.json
    const EndStops physical = *plain->joint(j).hardware().params().end_stops;
    const EndStops counted = *arm->joint(j).hardware().params().end_stops;
    const double a = m.true_position(j, counted.min_clicks), b = m.true_position(j, counted.max_clicks);
    EXPECT_NEAR(std::min(a, b), physical.min_clicks, 1.0) << j;
    EXPECT_NEAR(std::max(a, b), physical.max_clicks, 1.0) << j;
  }
}

TEST(ScaraMiscal, ASeedForTheXarmIsRefused) {
  EXPECT_THROW(make(make_miscalibration(MiscalArm::xarm, 7)), ArmctlError);
}

}  // namespace
}  // namespace armctl::joint_sim

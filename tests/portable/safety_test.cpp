// Safe in the field, on the portable code: motor polarity (both settings against both
// wirings), runaway and following-error faults (bridge off and held until clear_faults,
// drive commands refused meanwhile), and the read_diagnostic / clear_faults commands.
#include <gtest/gtest.h>

#include <cstdlib>

#include "joint_bus_harness.hpp"
#include "motor_plant.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_bus {
namespace {

using testing::BusHarness;
using testing::MotorPlant;

JointOptions with_polarity(MotorPolarity p) {
  JointOptions o;
  o.polarity = p;
  return o;
}

class SafetyTest : public ::testing::Test {
 protected:
  void start(MotorPolarity polarity, bool leads_swapped) {
    ASSERT_TRUE(joint.begin(1, default_tuning(), 9600, with_polarity(polarity)));
    joint.init_encoder(false, false);
    plant.leads_swapped = leads_swapped;
  }
  // Runs up to ms ticks; returns the tick at which a fault appeared (or -1).
  int run_ms(int ms) {
    for (int i = 0; i < ms; ++i) {
      plant.step(joint);
      if (joint.faults() != 0 && first_fault_ms < 0) first_fault_ms = elapsed_ms;
      ++elapsed_ms;
    }
    return first_fault_ms;
  }
  CommandResult cmd(int16_t c, int16_t d = 0) { return joint.execute(c, d); }
  JointController joint;
  MotorPlant plant;
  int elapsed_ms = 0;
  int first_fault_ms = -1;
};

TEST_F(SafetyTest, DefaultPolarityDrivesTheRightInputToCountUpLikeTheOriginalFirmware) {
  ASSERT_TRUE(joint.begin(1, default_tuning(), 9600));
  EXPECT_EQ(joint.options().polarity, MotorPolarity::original);
  joint.init_encoder(false, false);
  cmd(cmd_drive_to, 1000);
  joint.control_tick();
  joint.control_tick();
  // Target above position: the original firmware drives D11 ("right"), i.e. duty > 0.
  EXPECT_GT(joint.last_output().duty, 0);
  EXPECT_TRUE(joint.last_output().enable);

  JointController reversed;
  ASSERT_TRUE(reversed.begin(1, default_tuning(), 9600, with_polarity(MotorPolarity::reversed)));
  reversed.execute(cmd_drive_to, 1000);
  reversed.control_tick();
  reversed.control_tick();
  EXPECT_LT(reversed.last_output().duty, 0) << "reversed: D10 counts up";
}

TEST_F(SafetyTest, EachPolaritySettlesOnTheWiringItIsMeantFor) {
  for (const bool swapped : {false, true}) {
    SCOPED_TRACE(swapped ? "leads swapped, polarity reversed" : "original wiring and polarity");
    plant = MotorPlant();
    first_fault_ms = -1;
    start(swapped ? MotorPolarity::reversed : MotorPolarity::original, swapped);
    cmd(cmd_drive_to, 3000);
    run_ms(1500);
    EXPECT_NEAR(joint.position(), 3000, 2);
    EXPECT_EQ(joint.faults(), 0);
    cmd(cmd_drive_to, -2000);
    run_ms(1500);
    EXPECT_NEAR(joint.position(), -2000, 2);
    EXPECT_EQ(joint.faults(), 0);
  }
}

TEST_F(SafetyTest, WrongPolarityIsARunawayThatSwitchesTheBridgeOffAndHoldsIt) {
  for (const bool swapped : {true, false}) {
    SCOPED_TRACE(swapped ? "original polarity on swapped leads" : "reversed polarity on original wiring");
    plant = MotorPlant();
    elapsed_ms = 0;
    first_fault_ms = -1;
    start(swapped ? MotorPolarity::original : MotorPolarity::reversed, swapped);
    cmd(cmd_drive_to, 3000);
    while (joint.faults() == 0 && elapsed_ms < 1000) run_ms(1);
    const int at = first_fault_ms;
    ASSERT_GE(at, 0) << "no fault: the joint ran away unnoticed";
    EXPECT_EQ(joint.faults(), fault_runaway);
    // Stated time: runaway_ticks (100 ms) of a growing error while driving against it (plus
    // the first ticks before the error grows).
    EXPECT_GE(at, static_cast<int>(FaultMonitor::runaway_ticks));
    EXPECT_LE(at, static_cast<int>(FaultMonitor::runaway_ticks) + 50);
    EXPECT_LT(plant.position(), 0) << "it did run the wrong way";
    // First it brakes (bridge on, duty 0), then the bridge is off.
    EXPECT_TRUE(joint.braking());
    EXPECT_EQ(joint.last_output().duty, 0);
    run_ms(JointController::fault_brake_ticks);
    EXPECT_FALSE(joint.braking());
    EXPECT_FALSE(joint.last_output().enable);
    EXPECT_LT(std::abs(plant.speed_cps()), 1.0) << "braked to rest";
    // Held: the bridge stays off, drive commands are refused and change nothing.
    run_ms(500);
    EXPECT_FALSE(joint.last_output().enable);
    EXPECT_EQ(joint.last_output().duty, 0);
    EXPECT_EQ(cmd(cmd_drive_to, 100).status, status_bad_data);
    EXPECT_EQ(cmd(cmd_drive_dist, 100).status, status_bad_data);
    EXPECT_EQ(cmd(cmd_drive_dist_max, 100).status, status_bad_data);
    EXPECT_EQ(cmd(cmd_get_target).response, joint.position()) << "target follows position";
    const CommandResult faults = cmd(cmd_read_diagnostic, diagnostic_faults);
    EXPECT_EQ(faults.status, success_status(cmd_read_diagnostic));
    EXPECT_EQ(faults.response, fault_runaway);
  }
}

TEST_F(SafetyTest, ClearFaultsHoldsWhereTheJointIsAndDrivesAgain) {
  start(MotorPolarity::original, true);  // runs away
  cmd(cmd_drive_to, 3000);
  run_ms(600);
  ASSERT_EQ(joint.faults(), fault_runaway);
  run_ms(500);  // coasts to rest with the bridge off
  const int16_t at_rest = joint.position();
  // Rewire, then clear: the joint holds where it is (no jump to the old target).
  plant.leads_swapped = false;
  EXPECT_EQ(cmd(cmd_clear_faults).status, success_status(cmd_clear_faults));
  EXPECT_EQ(joint.faults(), 0);
  EXPECT_EQ(cmd(cmd_get_target).response, at_rest);
  run_ms(300);
  EXPECT_NEAR(joint.position(), at_rest, 2);
  EXPECT_TRUE(joint.last_output().enable);
  EXPECT_EQ(cmd(cmd_drive_to, 500).status, success_status(cmd_drive_to));
  run_ms(1500);
  EXPECT_NEAR(joint.position(), 500, 2);
  EXPECT_EQ(joint.faults(), 0);
}

TEST_F(SafetyTest, BrakingThroughAnOvershootIsNoRunaway) {
  // Aggressive tuning that overshoots: moving against the drive while braking must not
  // trip the runaway detection.
  JointTuning t = default_tuning();
  t.kd_q8 = 2 * 256;
  t.max_accel_cps2 = 1000000;
  ASSERT_TRUE(joint.begin(1, t, 9600));
  joint.init_encoder(false, false);
  double peak = 0;
  for (int16_t target : {int16_t{3000}, int16_t{-3000}, int16_t{200}}) {
    cmd(cmd_drive_to, target);
    for (int i = 0; i < 1500; ++i) {
      plant.step(joint);
      peak = std::max(peak, std::abs(plant.position() - target));
    }
    EXPECT_EQ(joint.faults(), 0) << target;
  }
  RecordProperty("largest_error_clicks", static_cast<int>(peak));
}

TEST_F(SafetyTest, AStalledJointRaisesTheFollowingErrorFault) {
  start(MotorPolarity::original, false);
  plant.stalled = true;
  cmd(cmd_drive_to, 20000);
  const int at = run_ms(3000);
  ASSERT_GE(at, 0);
  EXPECT_EQ(joint.faults(), fault_following_error);
  run_ms(JointController::fault_brake_ticks);
  EXPECT_FALSE(joint.last_output().enable);
  // A stall below the limit (3000 clicks) raises nothing however long it lasts.
  plant = MotorPlant();
  first_fault_ms = -1;
  start(MotorPolarity::original, false);
  plant.stalled = true;
  cmd(cmd_drive_to, 3000);
  EXPECT_LT(run_ms(5000), 0);
}

TEST_F(SafetyTest, LoopOffNeverFaults) {
  start(MotorPolarity::original, true);
  cmd(cmd_set_pid_state, 0);
  for (int i = 0; i < 2000; ++i) {
    plant.push(joint, 7);  // moved by hand, far and fast
    plant.step(joint);
  }
  EXPECT_EQ(joint.faults(), 0);
}

TEST_F(SafetyTest, ReadDiagnosticReportsEveryWordAndRefusesOthers) {
  JointOptions o;
  o.polarity = MotorPolarity::reversed;
  o.legacy_master = true;
  ASSERT_TRUE(joint.begin(4, default_tuning(), 9600, o));
  joint.init_encoder(false, false);
  joint.set_board_diagnostics(BoardDiagnostics{{3, 5, 7, 8}});
  joint.on_encoder_edge(true, true);  // both channels at once: one decoder error
  const auto word = [&](int16_t i) { return cmd(cmd_read_diagnostic, i).response; };
  EXPECT_EQ(word(diagnostic_faults), 0);
  EXPECT_EQ(word(diagnostic_bus_events_lost), 3);
  EXPECT_EQ(word(diagnostic_encoder_edges_lost), 5 + 1);
  EXPECT_EQ(word(diagnostic_uart_errors), 7);
  EXPECT_EQ(word(diagnostic_reset_cause), 8);
  EXPECT_EQ(word(diagnostic_settings), setting_motor_reversed | setting_legacy_master);
  // An abandoned transaction is counted.
  BusHarness bus(joint);
  bus.select(true);
  bus.drain();
  bus.select(false);  // before COMMAND, standard... but legacy keeps waiting: let it time out
  bus.advance(joint.transaction().timeout_us() + 10);
  EXPECT_EQ(word(diagnostic_abandoned), 1);
  for (int16_t bad : {int16_t{-1}, int16_t{diagnostic_count}, int16_t{32767}}) {
    EXPECT_EQ(cmd(cmd_read_diagnostic, bad).status, status_bad_data) << bad;
  }
}

TEST_F(SafetyTest, NewCommandsOverTheBusInTheStandardDialect) {
  start(MotorPolarity::original, false);
  BusHarness bus(joint);
  auto e = bus.transact(cmd_read_diagnostic, diagnostic_settings);
  EXPECT_EQ(e.response_word(), 0);
  EXPECT_EQ(e.status_word(), 500);
  e = bus.transact(cmd_clear_faults);
  EXPECT_TRUE(e.response.empty());
  EXPECT_EQ(e.status_word(), 510);
}

}  // namespace
}  // namespace armctl::joint_bus

// The split control step for the AVR: control_sample() (interrupts masked) then
// control_compute() (interrupts enabled) must behave exactly like control_tick(), and edges
// that arrive during the computation (between sample and compute) must be counted, not
// lost, and used by the next tick.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "joint_bus_harness.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_bus {
namespace {

using testing::EncoderDriver;

// A deterministic integer motor: velocity follows duty with a lag; returns clicks moved.
struct IntegerMotor {
  int32_t velocity_q8 = 0;
  int32_t position_q8 = 0;
  int32_t emitted = 0;
  int32_t advance(const DriveOutput& out) {
    const int32_t drive = out.enable ? out.duty * 25 : 0;
    velocity_q8 += (drive - velocity_q8) / 16;
    position_q8 += velocity_q8;
    const int32_t whole = position_q8 / 256;
    const int32_t moved = whole - emitted;
    emitted = whole;
    return moved;
  }
};

TEST(ControlSplit, SampleThenComputeEqualsControlTick) {
  JointController whole, split;
  ASSERT_TRUE(whole.begin(2, default_tuning(), 9600));
  ASSERT_TRUE(split.begin(2, default_tuning(), 9600));
  IntegerMotor motor_whole, motor_split;
  EncoderDriver enc_whole, enc_split;
  const int16_t targets[] = {3000, -1200, 40, 40, -32768, 500};
  for (int move = 0; move < 6; ++move) {
    for (JointController* j : {&whole, &split}) {
      ASSERT_EQ(j->execute(cmd_drive_to, targets[move]).status, 220);
      ASSERT_EQ(j->execute(cmd_set_speed, static_cast<int16_t>(30 + 14 * move)).status, 250);
    }
    if (move == 3) {
      ASSERT_EQ(whole.execute(cmd_home, 0).status, 110);
      ASSERT_EQ(split.execute(cmd_home, 0).status, 110);
    }
    for (int ms = 0; ms < 700; ++ms) {
      const DriveOutput a = whole.control_tick();
      split.control_sample();
      const DriveOutput b = split.control_compute();
      ASSERT_EQ(a.duty, b.duty) << "move " << move << " ms " << ms;
      ASSERT_EQ(a.enable, b.enable);
      ASSERT_EQ(whole.setpoint_q8(), split.setpoint_q8());
      ASSERT_EQ(whole.integral_q16(), split.integral_q16());
      enc_whole.move(whole, motor_whole.advance(a));
      enc_split.move(split, motor_split.advance(b));
    }
  }
  EXPECT_NE(whole.position(), 0) << "the motor really moved";
}

TEST(ControlSplit, EdgesDuringTheComputationAreKeptForTheNextTick) {
  JointController joint;
  ASSERT_TRUE(joint.begin(1, default_tuning(), 9600));
  joint.init_encoder(false, false);
  EncoderDriver encoder;
  joint.control_sample();           // count 0 taken
  encoder.move(joint, 5);           // edges arriving while control_compute() runs
  const DriveOutput during = joint.control_compute();
  EXPECT_EQ(during.duty, 0) << "the computation works on the sample (0 = target)";
  EXPECT_EQ(joint.encoder_count(), 5) << "no edge was lost";
  joint.control_sample();
  EXPECT_LT(joint.control_compute().duty, 0) << "the next tick sees the 5 clicks and drives back";
}

TEST(ControlSplit, HomeBetweenSampleAndComputeDoesNotUseTheOldCount) {
  JointController joint;
  ASSERT_TRUE(joint.begin(1, default_tuning(), 9600));
  joint.init_encoder(false, false);
  EncoderDriver encoder;
  encoder.move(joint, 3000);
  joint.control_sample();  // 3000
  ASSERT_EQ(joint.execute(cmd_home, 0).status, 110);
  const DriveOutput out = joint.control_compute();
  EXPECT_EQ(out.duty, 0) << "homed: position 0, target 0, no kick from the stale sample";
  EXPECT_EQ(joint.setpoint_q8(), 0);
  EXPECT_EQ(joint.integral_q16(), 0);
}

TEST(ControlSplit, UnconfiguredJointNeverDrives) {
  JointController joint;
  EXPECT_FALSE(joint.begin(0, default_tuning(), 9600));
  joint.control_sample();
  const DriveOutput out = joint.control_compute();
  EXPECT_FALSE(out.enable);
  EXPECT_EQ(out.duty, 0);
}

}  // namespace
}  // namespace armctl::joint_bus

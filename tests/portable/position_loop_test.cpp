// The position loop against a simple motor model: step moves, velocity and acceleration
// limits of the setpoint, set_speed 0 holds, loop off/on without jumps, home, anti-windup,
// no derivative kick, load rejection, and the int16/int32 position policy.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "motor_plant.hpp"
#include "portable/joint_controller.hpp"
#include "portable/pid_controller.hpp"
#include "portable/setpoint_ramp.hpp"

namespace armctl::joint_bus {
namespace {

using testing::MotorPlant;

class PositionLoopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(joint.begin(1, default_tuning(), 9600));
    joint.init_encoder(false, false);
  }
  void run_ms(int ms) {
    for (int i = 0; i < ms; ++i) plant.step(joint);
  }
  CommandResult cmd(int16_t c, int16_t d = 0) { return joint.execute(c, d); }
  JointController joint;
  MotorPlant plant;
};

TEST_F(PositionLoopTest, StepMoveSettlesOnTarget) {
  ASSERT_EQ(cmd(cmd_drive_to, 3000).status, 220);
  double peak = 0;
  for (int i = 0; i < 1500; ++i) {
    plant.step(joint);
    peak = std::max(peak, plant.position());
  }
  EXPECT_NEAR(joint.position(), 3000, 2);
  EXPECT_LT(peak, 3000 + 30) << "overshoot";
  RecordProperty("overshoot_clicks", static_cast<int>(peak - 3000));
  cmd(cmd_set_zone, 2);
  EXPECT_EQ(cmd(cmd_check_target_reached).response, 1);
}

TEST_F(PositionLoopTest, RejectsAConstantLoadWithTheIntegral) {
  plant.load_cps = 3000;  // needs ~30 PWM counts just to hold
  cmd(cmd_drive_to, 500);
  run_ms(3000);
  EXPECT_NEAR(joint.position(), 500, 1);
  EXPECT_GT(joint.integral_q16(), 20 * 65536);
}

TEST_F(PositionLoopTest, SetpointHonoursVelocityAndAccelerationLimits) {
  for (int16_t percent : {int16_t{100}, int16_t{37}, int16_t{5}}) {
    SCOPED_TRACE(percent);
    ASSERT_TRUE(joint.begin(1, default_tuning(), 9600));
    cmd(cmd_set_speed, percent);
    const int32_t vmax = joint.loop().ramp().speed_limit_q8();
    const int32_t amax = joint.loop().ramp().accel_q8();
    // 20000 c/s = 20 clicks/ms = 5120 Q8; 100000 c/s^2 = 0.1 click/ms^2 = 25.6 -> 26 Q8.
    EXPECT_EQ(vmax, 5120 * percent / 100);
    EXPECT_EQ(amax, 26);
    cmd(cmd_drive_to, 4000);
    int32_t last_sp = joint.setpoint_q8(), last_v = 0, peak_v = 0;
    for (int i = 0; i < 60000 && !(joint.setpoint_q8() == 4000 * 256 && last_v == 0); ++i) {
      if (i == 300) cmd(cmd_drive_to, -1500);  // reverse mid-move
      if (i == 700) cmd(cmd_drive_to, 4000);
      plant.step(joint);
      const int32_t v = joint.setpoint_q8() - last_sp;
      ASSERT_LE(std::abs(v), vmax) << "tick " << i;
      ASSERT_LE(std::abs(v - last_v), amax) << "tick " << i;
      peak_v = std::max(peak_v, std::abs(v));
      last_sp = joint.setpoint_q8();
      last_v = v;
    }
    EXPECT_EQ(joint.setpoint_q8(), 4000 * 256);
    EXPECT_EQ(last_v, 0);
    EXPECT_EQ(peak_v, vmax) << "cruises at the limit";
  }
}

// Ruckig-style: many random profiles straight on the ramp, including extreme tunings.
TEST(SetpointRamp, RandomProfilesStayWithinLimitsAndLandExactly) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 400; ++trial) {
    SetpointRamp ramp;
    // Speed limit >= 64 Q8 (250 clicks/s), so that the last move (<= 65536 clicks + what
    // the earlier ones left) ends within the 400,000 ticks below; limit < accel is common.
    const int32_t top = 64 + static_cast<int32_t>(rng() % (12800 - 63));
    const int32_t accel = 1 + static_cast<int32_t>(rng() % (trial % 2 ? 50 : 256));
    ramp.configure(top, accel);
    int percent = static_cast<int>(1 + rng() % 100);
    while (top * percent / 100 < 64) ++percent;
    ramp.set_speed_percent(static_cast<uint8_t>(percent));
    ramp.reset(static_cast<int32_t>(rng() % 2000000) - 1000000);
    const int32_t vmax = ramp.speed_limit_q8();
    int32_t target = 0, last_v = 0;
    int changes = 0;
    for (int tick = 0; tick < 400000; ++tick) {
      if (tick % 2000 == 0 && changes < 4) {
        target = (static_cast<int32_t>(rng() % 65536) - 32768) * 256 + static_cast<int32_t>(rng() % 256);
        ++changes;
      }
      const int32_t before = ramp.setpoint_q8();
      ramp.step(target);
      const int32_t v = ramp.setpoint_q8() - before;
      ASSERT_LE(std::abs(v), std::max(vmax, last_v == 0 ? 0 : std::abs(last_v))) << trial;
      ASSERT_LE(std::abs(v - last_v), ramp.accel_q8()) << "trial " << trial << " tick " << tick;
      last_v = v;
      if (changes == 4 && ramp.setpoint_q8() == target && v == 0) break;
    }
    ASSERT_EQ(ramp.setpoint_q8(), target) << "trial " << trial << " top " << top << " accel " << accel;
    ASSERT_EQ(ramp.velocity_q8(), 0);
  }
}

TEST_F(PositionLoopTest, SetSpeedZeroHoldsTheJoint) {
  cmd(cmd_drive_to, 20000);
  run_ms(400);
  ASSERT_EQ(cmd(cmd_set_speed, 0).status, 250);
  run_ms(600);  // decelerates at the limit: 20 clicks/ms at 0.1 click/ms^2 = 200 ms
  const int32_t held = joint.setpoint_q8();
  const int16_t position = joint.position();
  run_ms(1000);
  EXPECT_EQ(joint.setpoint_q8(), held);
  EXPECT_NEAR(joint.position(), position, 2);
  EXPECT_LT(joint.position(), 9000);
  EXPECT_EQ(cmd(cmd_check_target_reached).response, 0);
  cmd(cmd_set_speed, 50);
  run_ms(3000);
  EXPECT_NEAR(joint.position(), 20000, 2);
}

TEST_F(PositionLoopTest, LoopOffLetsTargetFollowAndReEnableDoesNotJump) {
  cmd(cmd_drive_to, 1000);
  run_ms(1500);
  ASSERT_EQ(cmd(cmd_set_pid_state, 0).status, 120);
  EXPECT_EQ(joint.target(), joint.position());
  EXPECT_FALSE(plant.step(joint).enable);
  plant.push(joint, -700);  // moved by hand
  const DriveOutput off = plant.step(joint);
  EXPECT_FALSE(off.enable);
  EXPECT_EQ(off.duty, 0);
  EXPECT_EQ(joint.target(), joint.position());
  EXPECT_EQ(joint.integral_q16(), 0);
  const int16_t here = joint.position();
  ASSERT_EQ(cmd(cmd_set_pid_state, 1).status, 120);
  EXPECT_EQ(joint.setpoint_q8(), here * 256);
  for (int i = 0; i < 200; ++i) {
    const DriveOutput on = plant.step(joint);
    ASSERT_TRUE(on.enable);
    ASSERT_LE(std::abs(on.duty), 2) << "no jump after re-enable, tick " << i;
  }
  EXPECT_NEAR(joint.position(), here, 1);
  // Enabling again while on changes nothing.
  cmd(cmd_drive_to, static_cast<int16_t>(here + 2000));
  run_ms(100);
  const int32_t sp = joint.setpoint_q8();
  const int32_t v = joint.setpoint_velocity_q8();
  cmd(cmd_set_pid_state, 1);
  EXPECT_EQ(joint.setpoint_q8(), sp);
  EXPECT_EQ(joint.setpoint_velocity_q8(), v);
}

TEST_F(PositionLoopTest, HomeClearsIntegralAndSetpointAndKeepsLoopState) {
  plant.load_cps = 2000;
  cmd(cmd_drive_to, 600);
  run_ms(2000);
  ASSERT_NE(joint.integral_q16(), 0);
  ASSERT_EQ(cmd(cmd_home).status, 110);
  EXPECT_EQ(joint.integral_q16(), 0);
  EXPECT_EQ(joint.setpoint_q8(), 0);
  EXPECT_EQ(joint.setpoint_velocity_q8(), 0);
  EXPECT_EQ(joint.position(), 0);
  EXPECT_EQ(joint.target(), 0);
  EXPECT_TRUE(joint.loop_enabled());
  run_ms(2000);
  EXPECT_NEAR(joint.position(), 0, 1) << "holds the new zero";
  cmd(cmd_set_pid_state, 0);
  cmd(cmd_home);
  EXPECT_FALSE(joint.loop_enabled());
}

TEST_F(PositionLoopTest, StalledJointDoesNotWindUp) {
  plant.stalled = true;
  // 3000 clicks: within the following-error limit, so the stall raises no fault.
  cmd(cmd_drive_to, 3000);
  run_ms(1000);
  // Once the output saturates in the error's direction the integral is frozen.
  EXPECT_EQ(joint.last_output().duty, 255);
  const int32_t frozen = joint.integral_q16();
  run_ms(2000);
  EXPECT_EQ(joint.integral_q16(), frozen);
  plant.stalled = false;
  double peak = 0;
  for (int i = 0; i < 3000; ++i) {
    plant.step(joint);
    peak = std::max(peak, plant.position());
  }
  EXPECT_LT(peak, 3000 + 50) << "released after a stall: no wind-up overshoot";
  EXPECT_NEAR(joint.position(), 3000, 2);
  EXPECT_EQ(joint.faults(), 0);
}

TEST_F(PositionLoopTest, IntegralNeverExceedsTheOutputRange) {
  JointTuning t = default_tuning();
  t.kp_q8 = 10;  // weak P: the integral has to do the work
  t.ki_q8 = 2000;
  ASSERT_TRUE(joint.begin(1, t, 9600));
  plant.stalled = true;
  cmd(cmd_drive_to, 200);
  for (int i = 0; i < 3000; ++i) {
    plant.step(joint);
    ASSERT_LE(std::abs(joint.integral_q16()), 255 * 65536);
  }
  EXPECT_EQ(joint.last_output().duty, 255);
}

TEST(PidController, DerivativeActsOnMeasurementNotOnSetpointChanges) {
  PidController pid;
  pid.configure(0, 0, 100 * 256, 255);
  pid.reset(0);
  EXPECT_EQ(pid.update(0, 0, 0), 0);
  EXPECT_EQ(pid.update(1000 * 256, 0, 0), 0) << "setpoint jump: no kick";
  EXPECT_EQ(pid.update(-5000 * 256, 0, 0), 0);
  EXPECT_EQ(pid.update(0, 0, 2 * 256), -200) << "measurement moved 2 clicks in a tick";
  EXPECT_EQ(pid.update(0, 0, 2 * 256), 0);
  EXPECT_EQ(pid.update(0, 1 * 256, 2 * 256), 100) << "feedforward of the setpoint velocity";
  EXPECT_EQ(pid.update(0, 1 * 256, 3 * 256), 0) << "tracking the setpoint velocity";
}

TEST(PidController, ProportionalAndSaturation) {
  PidController pid;
  pid.configure(3 * 256, 0, 0, 255);
  pid.reset(0);
  EXPECT_EQ(pid.update(10 * 256, 0, 0), 30);
  EXPECT_EQ(pid.update(-10 * 256, 0, 0), -30);
  EXPECT_EQ(pid.update(128, 0, 0), 2) << "half a click of error: 1.5 rounds to 2";
  EXPECT_EQ(pid.update(1000000 * 256, 0, 0), 255);
  EXPECT_EQ(pid.update(-1000000 * 256, 0, 0), -255);
  pid.configure(65535, 65535, 65535, 4095);  // extreme gains must not overflow
  pid.reset(0);
  const int32_t far = INT32_C(1) << 29;
  EXPECT_EQ(pid.update(far, 12800, -far), 4095);
  EXPECT_EQ(pid.update(-far, -12800, far), -4095);
}

TEST_F(PositionLoopTest, PositionSaturatesAtInt16WhileTheLoopUsesTheFullCount) {
  cmd(cmd_set_pid_state, 0);
  plant.push(joint, 33000);
  plant.step(joint);
  EXPECT_EQ(joint.encoder_count(), 33000);
  EXPECT_EQ(joint.position(), 32767);
  EXPECT_EQ(cmd(cmd_get_position).response, 32767);
  EXPECT_EQ(joint.target(), 32767);
  EXPECT_EQ(cmd(cmd_drive_dist_max, 1).status, status_bad_data);
  cmd(cmd_set_pid_state, 1);
  EXPECT_EQ(joint.setpoint_q8(), 33000 * 256) << "re-enable holds where the joint is";
  run_ms(2000);
  EXPECT_NEAR(joint.encoder_count(), 32767, 2) << "then the ramp brings it back in range";
}

TEST_F(PositionLoopTest, NoFloatNeededForTuningConversions) {
  JointTuning t = default_tuning();
  t.max_speed_cps = 1000000;     // clamped to 50000
  t.max_accel_cps2 = 1;          // clamped to 3906
  t.pwm_max = 30000;             // clamped to 4095
  ASSERT_TRUE(joint.begin(1, t, 9600));
  EXPECT_EQ(joint.loop().tuning().max_speed_cps, 50000);
  EXPECT_EQ(joint.loop().ramp().speed_limit_q8(), 12800);
  EXPECT_EQ(joint.loop().ramp().accel_q8(), 1);
  EXPECT_EQ(joint.loop().tuning().pwm_max, 4095);
  t.max_accel_cps2 = 20000000;   // clamped to 1,000,000 = 256 Q8 clicks/tick^2
  ASSERT_TRUE(joint.begin(1, t, 9600));
  EXPECT_EQ(joint.loop().tuning().max_accel_cps2, 1000000);
  EXPECT_EQ(joint.loop().ramp().accel_q8(), 256);
}

}  // namespace
}  // namespace armctl::joint_bus

// Step response and velocity limit of simulated joints, driven through bus bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "devices/joint_sim/arm_config.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "portable/joint_tuning.hpp"
#include "bus_bytes.hpp"

namespace armctl::joint_sim {
namespace {

using joint_bus::cmd_drive_to;
using joint_bus::cmd_set_speed;
using joint_bus::cmd_set_zone;
using testing::succeeded;
using testing::transact;

struct StepResult {
  double overshoot_clicks = 0.0;   // beyond the target, in the direction of the move
  double settle_ms = -1.0;         // from the end of drive_to until it stays in the zone
  double peak_speed_cps = 0.0;     // from encoder counts over 1 ms windows
  std::int16_t final_position = 0;
};

StepResult step(SimArm& arm, int joint, std::int16_t distance, int zone, int speed_percent,
                Duration observe) {
  auto& link = arm.link();
  EXPECT_TRUE(succeeded(transact(link, joint, cmd_set_zone, std::int16_t(zone)), cmd_set_zone));
  EXPECT_TRUE(succeeded(transact(link, joint, cmd_set_speed, std::int16_t(speed_percent)),
                        cmd_set_speed));
  const double start = arm.joint(joint).hardware().position_clicks();
  const double target = start + distance;
  EXPECT_TRUE(succeeded(transact(link, joint, cmd_drive_to, std::int16_t(std::lround(target))),
                        cmd_drive_to));
  const TimePoint t0 = arm.now();
  StepResult r;
  const double dir = distance > 0 ? 1.0 : -1.0;
  std::int64_t last_count = arm.joint(joint).hardware().encoder_count();
  TimePoint last_outside = t0;
  for (TimePoint t = t0; t < t0 + observe; t += std::chrono::milliseconds(1)) {
    arm.run_until(t + std::chrono::milliseconds(1));
    const JointHardware& hw = arm.joint(joint).hardware();
    const double pos = hw.position_clicks();
    r.overshoot_clicks = std::max(r.overshoot_clicks, (pos - target) * dir);
    r.peak_speed_cps =
        std::max(r.peak_speed_cps, std::abs(double(hw.encoder_count() - last_count)) * 1000.0);
    last_count = hw.encoder_count();
    if (std::abs(double(arm.joint(joint).controller().position()) - target) > zone) {
      last_outside = arm.now();
    }
  }
  r.settle_ms = std::chrono::duration<double, std::milli>(last_outside - t0).count();
  r.final_position = arm.joint(joint).controller().position();
  return r;
}

// Stated performance with config/scara.arm.json (docs/simulator.md, "Step response"): a 3000
// click step at 100 % speed with zone 10 settles (stays in the zone for good) within 700 ms
// on every joint but SHOULDER (1000 ms, slower profile for its inertia), and overshoots by
// at most 5 clicks.
TEST(StepResponse, EveryJointSettlesInZoneWithBoundedOvershoot) {
  auto arm = SimArm::from_default_config();
  for (int j = 1; j <= 7; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j));
    const StepResult r = step(*arm, j, 3000, 10, 100, std::chrono::seconds(3));
    std::printf("joint %d: overshoot %.1f clicks, settle %.0f ms, peak %.0f cps, final %d\n", j,
                r.overshoot_clicks, r.settle_ms, r.peak_speed_cps, r.final_position);
    EXPECT_LE(r.overshoot_clicks, 5.0);
    EXPECT_LE(r.settle_ms, j == 2 ? 1000.0 : 700.0);
    EXPECT_NEAR(r.final_position, 3000, 10);
    EXPECT_TRUE(succeeded(transact(arm->link(), j, joint_bus::cmd_check_target_reached),
                          joint_bus::cmd_check_target_reached));
  }
}

TEST(StepResponse, NegativeStepSettlesToo) {
  auto arm = SimArm::from_default_config();
  const StepResult r = step(*arm, 4, -2000, 5, 100, std::chrono::seconds(2));
  EXPECT_LE(r.overshoot_clicks, 10.0);
  EXPECT_LE(r.settle_ms, 700.0);
  EXPECT_NEAR(r.final_position, -2000, 5);
}

TEST(VelocityLimit, HalfSpeedPeakStaysWithinHalfTheMaximum) {
  auto arm = SimArm::from_default_config();
  for (int j : {1, 2, 5}) {
    SCOPED_TRACE("joint " + std::to_string(j));
    const double max_cps = arm->config().joint(j).tuning.max_speed_cps;
    auto& link = arm->link();
    ASSERT_TRUE(succeeded(transact(link, j, cmd_set_speed, 50), cmd_set_speed));
    ASSERT_TRUE(succeeded(transact(link, j, cmd_drive_to, 20000), cmd_drive_to));
    // Peak over 10 ms windows of encoder counts and of the instantaneous motor speed.
    double peak_window = 0.0;
    double peak_instant = 0.0;
    double peak_setpoint = 0.0;
    std::int64_t last = arm->joint(j).hardware().encoder_count();
    for (int ms = 0; ms < 6000; ms += 10) {
      for (int k = 0; k < 10; ++k) {
        arm->advance(std::chrono::milliseconds(1));
        peak_instant = std::max(peak_instant,
                                std::abs(arm->joint(j).hardware().joint_velocity_clicks_s()));
        peak_setpoint = std::max(
            peak_setpoint,
            std::abs(double(arm->joint(j).controller().setpoint_velocity_q8())) * 1000.0 / 256.0);
      }
      const std::int64_t now = arm->joint(j).hardware().encoder_count();
      peak_window = std::max(peak_window, std::abs(double(now - last)) * 100.0);
      last = now;
    }
    std::printf("joint %d at 50 %%: peak %.0f cps over 10 ms, %.0f cps instantaneous, limit %.0f\n",
                j, peak_window, peak_instant, 0.5 * max_cps);
    // The setpoint obeys the limit exactly; the joint itself overshoots it briefly (PID with
    // no velocity feed-forward catching up after the acceleration phase), by at most 6 %.
    EXPECT_LE(peak_setpoint, 0.5 * max_cps);
    EXPECT_LE(peak_window, 0.5 * max_cps * 1.06);
    EXPECT_LE(peak_instant, 0.5 * max_cps * 1.06);
    EXPECT_GE(peak_window, 0.5 * max_cps * 0.95);  // and it does move at about that speed
    EXPECT_EQ(arm->joint(j).controller().position(), 20000);
  }
}

// A board flashed with `make flash` and no tuning written has the portable default_tuning()
// (docs/firmware.md). On every simulated joint, the heaviest (SHOULDER) included, it must
// follow the steps the bench drives (3000 clicks out, 4000 back) without a false runaway
// fault: braking a heavy joint through its overshoot moves it against the drive for longer
// than the runaway window, but slower and slower, which a runaway (motor leads swapped) never
// does. (bench_firmware found joint 2 faulted as a runaway with these steps.)
TEST(StepResponse, TheDefaultTuningFollowsStepsOnEveryJointWithoutAFault) {
  ArmConfig config = load_arm_config(default_arm_config_path());
  for (auto& joint : config.joints) joint.tuning = joint_bus::default_tuning();
  SimArm arm(config);
  for (int j = 1; j <= 7; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j));
    for (std::int16_t distance : {std::int16_t{3000}, std::int16_t{-4000}, std::int16_t{1000}}) {
      const StepResult r = step(arm, j, distance, 10, 100, std::chrono::seconds(2));
      EXPECT_EQ(arm.joint(j).controller().faults(), 0) << "after a step of " << distance;
      std::printf("joint %d default tuning, step %d: overshoot %.1f clicks, settle %.0f ms\n", j, distance,
                  r.overshoot_clicks, r.settle_ms);
    }
  }
}

}  // namespace
}  // namespace armctl::joint_sim

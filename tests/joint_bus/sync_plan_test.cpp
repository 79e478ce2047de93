#include "devices/joint_bus/sync_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace armctl::joint_bus {
namespace {

using namespace std::chrono_literals;
const JointProfile kProfile{12000, 40000};

TEST(MoveSeconds, TrapezoidAndTriangle) {
  // 12000 clicks at full speed: 1 s cruise + 0.3 s for the ramps.
  EXPECT_NEAR(move_seconds(12000, 100, kProfile), 1.3, 1e-9);
  // Short move never reaches top speed: 2 sqrt(d/a).
  EXPECT_NEAR(move_seconds(1000, 100, kProfile), 2 * std::sqrt(1000.0 / 40000), 1e-9);
  EXPECT_EQ(move_seconds(0, 50, kProfile), 0);
  EXPECT_GT(move_seconds(12000, 10, kProfile), move_seconds(12000, 11, kProfile));
}

TEST(QuantizedProfile, MatchesTheJointsFixedPoint) {
  JointProfile q = as_quantized_by_joint({12000, 40000});
  EXPECT_NEAR(q.max_speed_cps, 12000, 1);
  EXPECT_NEAR(q.max_accel_cps2, 10 * 1e6 / 256, 1e-6);  // 10 Q8 clicks/tick^2
}

TEST(SyncPlan, EveryJointEndsAtTheCommonInstant) {
  std::vector<PlanInput> in{{1, 8000, kProfile}, {2, 300, kProfile}, {3, 0, kProfile}, {4, 5000, kProfile}};
  SyncPlan plan = plan_synchronized_move(in, 2000ms, 10ms, 12ms);
  EXPECT_EQ(plan.total, 2000ms);
  for (const auto& j : plan.joints) {
    EXPECT_NEAR(std::chrono::duration<double>(j.start + j.duration).count(), 2.0, 1e-6) << j.joint;
    EXPECT_GE(j.start, 10ms);
    EXPECT_GE(j.percent, 1);
    EXPECT_LE(j.percent, 100);
  }
  // Drive commands are at least one transaction apart.
  for (std::size_t a = 0; a < plan.joints.size(); ++a)
    for (std::size_t b = a + 1; b < plan.joints.size(); ++b)
      EXPECT_GE(std::chrono::abs(plan.joints[a].start - plan.joints[b].start), 12ms);
}

TEST(SyncPlan, TooShortATimeIsStretchedToWhatTheSlowestJointCanDo) {
  std::vector<PlanInput> in{{1, 12000, kProfile}, {2, 100, kProfile}};
  SyncPlan plan = plan_synchronized_move(in, 100ms, 0ms, 10ms);
  EXPECT_NEAR(std::chrono::duration<double>(plan.total).count(), 1.3, 1e-6);
  EXPECT_EQ(plan.joints[0].percent, 100);
}

TEST(SyncPlan, MovingStartArrivesAtTheCommonInstantWithoutTurning) {
  // A joint cruising at 6000 clicks/s toward 20000, re-targeted to 3000 clicks ahead in 800 ms.
  joint_bus::SetpointRamp ramp;
  ramp.configure((12000 * 32 + 62) / 125, (40000 * 32 + 62500) / 125000);
  ramp.set_speed_percent(50);
  ramp.reset(0);
  for (int i = 0; i < 400; ++i) ramp.step(20000 * 256);
  ASSERT_GT(ramp.velocity_q8(), 0);
  const std::int32_t from = ramp.setpoint_q8();
  std::vector<PlanInput> in(1);
  in[0].joint = 1;
  in[0].profile = as_quantized_by_joint(kProfile);
  in[0].zone = 20;
  in[0].moving = MovingStart{ramp, 20000 * 256, 0ms};
  in[0].target_q8 = from + 3000 * 256;
  in[0].distance = 3000;
  SyncPlan plan = plan_synchronized_move(in, 800ms, 10ms, 12ms);
  ASSERT_EQ(plan.total, 800ms);
  const PlannedJoint& j = plan.joints[0];
  EXPECT_TRUE(j.drive_first);
  auto arrival = moving_arrival(*in[0].moving, in[0].target_q8, j.start, j.speed_at, j.percent, j.switch_percent,
                                j.switch_at, 2000ms);
  ASSERT_TRUE(arrival);
  EXPECT_LE(std::chrono::abs(*arrival - 800ms), 3ms);
  EXPECT_EQ(j.start + j.duration, *arrival);
}

}  // namespace
}  // namespace armctl::joint_bus

// The stall watch alone, on a simulated clock: a joint driven but standing still is stalled
// once the stated time has passed (not before), with how long; a joint that moves, that is
// not driven (there, or within its threshold, or left alone by the move) or that is not
// watched (the gripper) never is; noise within the "moves" threshold does not reset it.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "arm/stall_watch.hpp"
#include "core/clock.hpp"

namespace armctl::arm {
namespace {

using std::chrono::milliseconds;

constexpr StallThresholds kJoint{0.035, 0.0175};  // 2 deg driven, 1 deg moves

struct Reads {
  SimClock clock;
  StallWatch watch{{kJoint, kJoint, StallThresholds{}}};  // the third: not watched (a gripper)
  // Advances the clock by `step` and reads.
  std::optional<JointStall> read(milliseconds step, std::vector<double> at, std::vector<std::optional<double>> to) {
    clock.advance_to(clock.now() + step);
    return watch.read(clock.now(), at, to);
  }
};

TEST(StallWatch, ADrivenJointStandingStillStallsAfterTheStatedTime) {
  Reads r;
  // Joint 0 driven to 0.5 rad, standing at 0.1; read every 100 ms.
  for (int k = 0; k < 5; ++k) EXPECT_FALSE(r.read(milliseconds(100), {0.1, 0, 0}, {0.5, 0.0, std::nullopt})) << k;
  // 400 ms since the first driven read: not yet; at 500 ms it is.
  const auto s = r.read(milliseconds(100), {0.1, 0, 0}, {0.5, 0.0, std::nullopt});
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->joint, 0);
  EXPECT_DOUBLE_EQ(s->position, 0.1);
  EXPECT_DOUBLE_EQ(s->driven_to, 0.5);
  EXPECT_NEAR(s->seconds, 0.5, 1e-9);
  EXPECT_EQ(kStallTime, milliseconds(500));
}

TEST(StallWatch, AJointThatMovesOrArrivesNeverStalls) {
  Reads r;
  // Behind its target by far more than the threshold, but moving 2 deg every 100 ms.
  double at = 0;
  for (int k = 0; k < 30; ++k, at += 0.035) EXPECT_FALSE(r.read(milliseconds(100), {at, 0, 0}, {2.0, 0.0, 0.0}));
  // Within the driven threshold of where it is driven (a servo's lag): standing is fine.
  for (int k = 0; k < 30; ++k) EXPECT_FALSE(r.read(milliseconds(100), {1.0, 0, 0}, {1.03, 0.0, 0.0}));
}

TEST(StallWatch, NoiseWithinTheMovesThresholdDoesNotResetTheTime) {
  Reads r;
  // A servo pushing against an obstacle jitters by a unit or two: still standing.
  std::optional<JointStall> s;
  for (int k = 0; k < 6 && !s; ++k) s = r.read(milliseconds(100), {0, 0.2 + (k % 2) * 0.004, 0}, {0.0, -0.3, 0.0});
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->joint, 1);
}

TEST(StallWatch, ATimeRestartsWhenTheJointMovesOrIsNoLongerDriven) {
  Reads r;
  for (int k = 0; k < 4; ++k) EXPECT_FALSE(r.read(milliseconds(100), {0.1, 0, 0}, {0.5, 0.0, 0.0}));
  // It moved 3 deg: the 500 ms count from here.
  for (int k = 0; k < 5; ++k) EXPECT_FALSE(r.read(milliseconds(100), {0.15, 0, 0}, {0.5, 0.0, 0.0})) << k;
  // Not driven for one read (the move left it alone): the count starts again after it.
  EXPECT_FALSE(r.read(milliseconds(100), {0.15, 0, 0}, {std::nullopt, 0.0, 0.0}));
  for (int k = 0; k < 5; ++k) EXPECT_FALSE(r.read(milliseconds(100), {0.15, 0, 0}, {0.5, 0.0, 0.0})) << k;
  EXPECT_TRUE(r.read(milliseconds(100), {0.15, 0, 0}, {0.5, 0.0, 0.0}));
}

TEST(StallWatch, AJointNotWatchedOrAWatchTurnedOffNeverStalls) {
  Reads r;
  // The gripper closed on a part: driven, standing, for seconds.
  for (int k = 0; k < 50; ++k) EXPECT_FALSE(r.read(milliseconds(100), {0, 0, 0.01}, {0.0, 0.0, 0.03}));
  SimClock clock;
  StallWatch off({kJoint}, Duration{0});
  for (int k = 0; k < 50; ++k) {
    clock.advance_to(clock.now() + milliseconds(100));
    EXPECT_FALSE(off.read(clock.now(), std::vector<double>{0.1}, std::vector<std::optional<double>>{0.5}));
  }
}

}  // namespace
}  // namespace armctl::arm

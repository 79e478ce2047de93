#include "core/clock.hpp"

#include <gtest/gtest.h>

namespace armctl {
namespace {

TEST(WireTime, EightBytesAt9600IsEightPointThreeMilliseconds) {
  EXPECT_EQ(wire_time(8, 9600), Duration{8'333'333});
  EXPECT_EQ(wire_time(1, 115200), Duration{86'805});
}

TEST(SimClock, MovesOnlyWhenAdvancedAndNeverBackwards) {
  SimClock clock;
  EXPECT_EQ(clock.now().time_since_epoch(), Duration{0});
  clock.advance(Duration{5});
  clock.advance_to(TimePoint{Duration{3}});
  EXPECT_EQ(clock.now().time_since_epoch(), Duration{5});
  clock.advance_to(TimePoint{Duration{9}});
  EXPECT_EQ(clock.now().time_since_epoch(), Duration{9});
}

}  // namespace
}  // namespace armctl

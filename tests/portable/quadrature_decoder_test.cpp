// 4x quadrature decoding in both directions; invalid double transitions are errors.
#include <gtest/gtest.h>

#include "joint_bus_harness.hpp"
#include "portable/quadrature_decoder.hpp"

namespace armctl::joint_bus {
namespace {

void levels(int32_t phase, bool* a, bool* b) { testing::EncoderDriver::levels(phase, a, b); }

TEST(QuadratureDecoder, CountsEveryEdgeUpAndDown) {
  QuadratureDecoder d;
  d.reset(false, false);
  bool a, b;
  for (int32_t p = 1; p <= 4000; ++p) {
    levels(p, &a, &b);
    d.on_edge(a, b);
    ASSERT_EQ(d.count(), p);
  }
  for (int32_t p = 3999; p >= -4000; --p) {
    levels(p, &a, &b);
    d.on_edge(a, b);
    ASSERT_EQ(d.count(), p);
  }
  EXPECT_EQ(d.errors(), 0u);
}

TEST(QuadratureDecoder, DirectionFollowsWhichChannelLeads) {
  QuadratureDecoder d;
  d.reset(false, false);
  d.on_edge(false, true);  // B rises first: up
  EXPECT_EQ(d.count(), 1);
  d.on_edge(false, false);
  d.on_edge(true, false);  // A rises first: down
  EXPECT_EQ(d.count(), -1);
}

TEST(QuadratureDecoder, DoubleTransitionsAreErrorsNotCounts) {
  QuadratureDecoder d;
  d.reset(false, false);
  d.on_edge(true, true);  // 00 -> 11: both changed, an edge was missed
  EXPECT_EQ(d.count(), 0);
  EXPECT_EQ(d.errors(), 1u);
  d.on_edge(false, false);  // 11 -> 00
  d.on_edge(false, true);   // 00 -> 01: valid again
  d.on_edge(true, false);   // 01 -> 10: invalid
  EXPECT_EQ(d.count(), 1);
  EXPECT_EQ(d.errors(), 3u);
  // The decoder takes the new levels as reference: counting resumes from 10.
  d.on_edge(false, false);  // 10 -> 00 is +1
  EXPECT_EQ(d.count(), 2);
}

TEST(QuadratureDecoder, RepeatedLevelsAreIgnored) {
  QuadratureDecoder d;
  d.reset(true, false);
  d.on_edge(true, false);
  EXPECT_EQ(d.count(), 0);
  EXPECT_EQ(d.errors(), 0u);
}

TEST(QuadratureDecoder, ResetTakesLevelsWithoutCounting) {
  QuadratureDecoder d;
  d.reset(true, true);
  EXPECT_EQ(d.count(), 0);
  d.on_edge(true, false);  // 11 -> 10 is +1
  EXPECT_EQ(d.count(), 1);
  EXPECT_EQ(d.errors(), 0u);
}

TEST(QuadratureDecoder, ErrorCounterSaturates) {
  QuadratureDecoder d;
  d.reset(false, false);
  for (int i = 0; i < 70000; ++i) d.on_edge(i % 2 == 0, i % 2 == 0);
  EXPECT_EQ(d.errors(), 65535u);
  d.clear_errors();
  EXPECT_EQ(d.errors(), 0u);
}

TEST(QuadratureDecoder, CountIsNotLimitedToInt16) {
  QuadratureDecoder d;
  d.reset(false, false);
  bool a, b;
  for (int32_t p = 1; p <= 40000; ++p) {
    levels(p, &a, &b);
    d.on_edge(a, b);
  }
  EXPECT_EQ(d.count(), 40000);
}

}  // namespace
}  // namespace armctl::joint_bus

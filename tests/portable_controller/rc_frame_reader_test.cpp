#include <gtest/gtest.h>

#include <vector>

#include "portable_controller/rc_frame_reader.hpp"

namespace armctl::controller {
namespace {

struct Seen {
  int command;
  std::vector<std::uint8_t> data;
};

std::vector<Seen> feed(RcFrameReader& r, const std::vector<std::uint8_t>& bytes, std::uint32_t start_us = 0,
                       std::uint32_t step_us = 1000) {
  std::vector<Seen> out;
  std::uint32_t t = start_us;
  for (std::uint8_t b : bytes) {
    if (r.on_byte(b, t)) out.push_back(Seen{r.command(), {r.data(), r.data() + r.data_length()}});
    t += step_us;
  }
  return out;
}

TEST(RcFrameReader, ReadsFramesBackToBack) {
  RcFrameReader r;
  auto seen = feed(r, {0x55, 0x55, 0x02, 0x0F, 0x55, 0x55, 0x04, 0x15, 0x01, 0x03});
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].command, 15);
  EXPECT_TRUE(seen[0].data.empty());
  EXPECT_EQ(seen[1].command, 21);
  EXPECT_EQ(seen[1].data, (std::vector<std::uint8_t>{1, 3}));
}

TEST(RcFrameReader, ResynchronisesAfterGarbageAndBadLengths) {
  RcFrameReader r;
  // garbage, LEN 1 (too short), LEN 63 (cannot fit a report), then `55 55 55 02 0F`.
  auto seen = feed(r, {0x00, 0x55, 0x12, 0x55, 0x55, 0x01, 0x55, 0x55, 0x3F, 0x55, 0x55, 0x55, 0x02, 0x0F});
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].command, 15);
  EXPECT_GT(r.discarded_bytes(), 0);
}

TEST(RcFrameReader, DropsAPartialFrameOlderThanTheGap) {
  RcFrameReader r(frame_gap_us(9600));
  EXPECT_EQ(frame_gap_us(9600), 50000u) << "20 byte times are 20.8 ms: the 50 ms floor applies";
  EXPECT_EQ(frame_gap_us(1200), 166666u);
  // `55 55 08 03 01` (a move begun), then 60 ms later a battery request.
  auto first = feed(r, {0x55, 0x55, 0x08, 0x03, 0x01}, 0);
  auto second = feed(r, {0x55, 0x55, 0x02, 0x0F}, 4000 + 60000);
  EXPECT_TRUE(first.empty());
  ASSERT_EQ(second.size(), 1u) << "the new frame is read on its own";
  EXPECT_EQ(second[0].command, 15);
  EXPECT_EQ(r.torn_frames(), 1);
}

TEST(RcFrameReader, JoinsAFrameWhosePartsComeWithinTheGap) {
  RcFrameReader r(frame_gap_us(9600));
  auto first = feed(r, {0x55, 0x55, 0x04, 0x15}, 0);
  auto second = feed(r, {0x01, 0x02}, 3000 + 45000);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(r.torn_frames(), 0);
}

TEST(RcFrameReader, GapIsMeasuredAcrossTheClockWrap) {
  RcFrameReader r(frame_gap_us(9600));
  auto seen = feed(r, {0x55, 0x55, 0x02, 0x0F}, 0xFFFFF000u, 1000);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(r.torn_frames(), 0);
}

}  // namespace
}  // namespace armctl::controller

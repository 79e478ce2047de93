// Malformed and refused frames: ignored with no effect, counted, never a crash.
#include "harness.hpp"

#include <random>

namespace armctl::xarm::test {
namespace {

TEST(Malformed, SharedVectorsAreIgnoredAndCounted) {
  for (const auto& m : malformed_vectors()) {
    SCOPED_TRACE(m["expect"].get<std::string>());
    Emulated e;
    e.send(hex(m["bytes"].get<std::string>()));
    e.advance_ms(2000);
    auto expect = m["expect"].get<std::string>();
    if (expect.find("then GetBatteryVoltage") != std::string::npos) {
      EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("GetBatteryVoltage reply 7500 mV")));
      EXPECT_EQ(e.stats().discarded_bytes, 1u);
      continue;
    }
    EXPECT_TRUE(e.out.empty());
    for (std::uint8_t s = 1; s <= 6; ++s) EXPECT_EQ(e.position(s), 500);
    auto st = e.stats();
    EXPECT_EQ(st.handled, 0u);
    EXPECT_GE(st.ignored() + st.bad_lengths, 1u);
  }
}

TEST(Malformed, EachReasonHasItsCounter) {
  Emulated e;
  e.send(hex("55 55 02 63"));                    // unknown CMD
  e.send(hex("55 55 05 15 03 01 02"));           // count 3 with 2 IDs
  e.send(hex("55 55 08 03 01 E8 03 07 F4 01"));  // servo 7 on a 6-servo arm
  e.send(rc::BusServoInfoWrite{1, 0, 400, 4500, 12000, 85, 0, 0});
  e.send(rc::MultiServoMove{100, {{1, 401}}});  // beyond servo 1's limit
  e.send(rc::GroupDownloadEnd{3});              // no download in progress
  e.send(rc::GroupRun{3, 1});                   // nothing stored
  auto st = e.stats();
  EXPECT_EQ(st.unknown_command, 1u);
  EXPECT_EQ(st.invalid_frame, 1u);
  EXPECT_EQ(st.unknown_servo, 1u);
  EXPECT_EQ(st.out_of_range, 1u);
  EXPECT_EQ(st.download_rejected, 1u);
  EXPECT_EQ(st.refused, 1u);
  EXPECT_EQ(st.ignored(), 6u);
  EXPECT_EQ(st.handled, 1u);
  EXPECT_NE(e.emulator.board().last_rejection().find("group 3"), std::string::npos);
}

TEST(Malformed, NoPartialEffectWhenOneEntryIsBad) {
  Emulated e;
  e.send(rc::ServoOffsetAdjust{2, 7});
  // MultiServoOff of 1 and 9: servo 9 is absent, so servo 1 keeps its torque.
  e.send(hex("55 55 05 14 02 01 09"));
  EXPECT_TRUE(e.emulator.servos().torque(1));
  // ServoOffsetWrite of 2 and 8: nothing saved.
  e.send(hex("55 55 05 16 02 02 08"));
  EXPECT_EQ(e.emulator.servos().saved_offset(2), 0);
  // MultiServoMove with servo 1 fine and servo 2 beyond 1000: nobody moves.
  e.send(hex("55 55 0B 03 02 00 00 01 C8 00 02 E9 03"));
  e.advance_ms(1000);
  EXPECT_EQ(e.position(1), 500);
  EXPECT_EQ(e.stats().ignored(), 3u);
}

TEST(Malformed, RandomBytesNeverCrashOrMoveOutOfRange) {
  Emulated e;
  std::mt19937 rng(1234);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> pick(0, 9);
  for (int round = 0; round < 20000; ++round) {
    std::vector<std::uint8_t> chunk;
    int n = 1 + pick(rng) * 3;
    for (int i = 0; i < n; ++i) {
      // Bias towards frame-like input so the decoder is exercised, not just the hunt.
      if (pick(rng) < 2) chunk.insert(chunk.end(), {0x55, 0x55});
      chunk.push_back(static_cast<std::uint8_t>(byte(rng)));
    }
    e.send(chunk);
    e.advance_ms(pick(rng) * 10);
    for (std::uint8_t s = 1; s <= 6; ++s) {
      double p = e.emulator.servos().commanded_position(s);
      ASSERT_TRUE(p >= 0 && p < XarmServos::kTurn) << "servo " << int(s) << " at " << p;
    }
  }
  EXPECT_GT(e.stats().frames, 100u);
  EXPECT_GT(e.stats().discarded_bytes, 1000u);
}

}  // namespace
}  // namespace armctl::xarm::test

namespace armctl::xarm::test {
namespace {

// The reproduction: a host dies mid-frame, another reads servo 1 two seconds later.
TEST(TornFrame, ADeadHostsHalfFrameMovesNothing) {
  Emulated e;
  e.send(hex("55 55 08 03 01"));
  e.advance_ms(2000);
  e.send(hex("55 55 04 15 01 01"));
  e.advance_ms(100);
  ASSERT_EQ(e.out.size(), 1u);  // the read is answered
  EXPECT_EQ(e.out[0].cmd, 0x15);
  e.advance_ms(30000);
  for (std::uint8_t s = 1; s <= 6; ++s) EXPECT_EQ(e.position(s), 500) << int(s);
  EXPECT_EQ(e.stats().torn_frames, 1u);
}

TEST(TornFrame, AFrameSplitAcrossWritesIsStillAccepted) {
  Emulated e;
  e.send(hex("55 55 08 03 01"));
  e.advance_ms(20);
  e.send(hex("F4 01 01 C8 00"));  // servo 1 to 200 over 500 ms
  e.advance_ms(1000);
  EXPECT_EQ(e.position(1), 200);
  EXPECT_EQ(e.stats().torn_frames, 0u);
}

}  // namespace
}  // namespace armctl::xarm::test

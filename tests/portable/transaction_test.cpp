// The transaction state machine: timeouts, abandon and recovery, early select drops,
// bytes for other joints, the uint32 microsecond wrap, and random event sequences.
#include <gtest/gtest.h>

#include <random>

#include "joint_bus_harness.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_bus {
namespace {

using testing::BusHarness;
using State = BusTransaction::State;

class TransactionTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(joint.begin(4, default_tuning(), 9600)); }
  uint32_t timeout() const { return joint.transaction().timeout_us(); }
  // After any abandon, the joint must serve the next transaction normally.
  void expect_recovers() {
    const auto e = bus.transact(cmd_ping, int16_t{-99});
    EXPECT_EQ(e.ready_word(), 4);
    EXPECT_EQ(e.response_word(), -99);
    EXPECT_EQ(e.status_word(), 100);
  }
  JointController joint;
  BusHarness bus{joint};
};

TEST_F(TransactionTest, TimeoutIsFourWordTimesPlusTwoMilliseconds) {
  EXPECT_EQ(timeout(), 8333u + 2000u);
  JointController fast;
  fast.begin(1, default_tuning(), 115200);
  EXPECT_EQ(fast.transaction().timeout_us(), 694u + 2000u);
}

TEST_F(TransactionTest, SilentMasterAfterSelectIsAbandonedAndTxReleased) {
  bus.select(true);
  EXPECT_TRUE(joint.tx_enabled());
  EXPECT_EQ(bus.drain().size(), 2u);
  uint32_t deadline = 0;
  ASSERT_TRUE(joint.next_deadline_us(&deadline));
  bus.advance(deadline - bus.now_us() - 1);
  EXPECT_EQ(joint.transaction().state(), State::await_command) << "not before the deadline";
  bus.advance(1);
  EXPECT_EQ(joint.transaction().state(), State::abandoned);
  EXPECT_FALSE(joint.tx_enabled());
  bus.send_word(cmd_ping);  // bytes while abandoned are ignored
  bus.send_word(5);
  EXPECT_TRUE(bus.drain().empty());
  bus.select(false);
  EXPECT_TRUE(bus.drain().empty()) << "no STATUS for an abandoned transaction";
  EXPECT_EQ(joint.transaction().state(), State::idle);
  EXPECT_EQ(joint.transaction().abandoned_count(), 1u);
  expect_recovers();
}

TEST_F(TransactionTest, SilenceBetweenCommandAndDataAbandonsWithoutExecuting) {
  bus.select(true);
  bus.drain();
  bus.send_word(cmd_drive_to);
  bus.advance(timeout() + 1);
  EXPECT_EQ(joint.transaction().state(), State::abandoned);
  bus.send_word(1000);
  EXPECT_EQ(joint.target(), 0) << "the command never completed";
  bus.select(false);
  EXPECT_TRUE(bus.drain().empty());
  expect_recovers();
}

TEST_F(TransactionTest, SilenceInsideAWordAbandons) {
  bus.select(true);
  bus.drain();
  bus.send(0x0C);
  bus.advance(timeout() + 1);
  EXPECT_EQ(joint.transaction().state(), State::abandoned);
  bus.select(false);
  expect_recovers();
}

TEST_F(TransactionTest, LateByteWithoutPollIsTreatedAsTimedOut) {
  joint.on_select(true, 1000);
  uint8_t b;
  while (joint.next_tx_byte(&b)) {}
  joint.on_rx_byte(0x0C, 1000 + timeout() + 1);  // poll() was never called in between
  EXPECT_EQ(joint.transaction().state(), State::abandoned);
}

TEST_F(TransactionTest, SelectDroppedEarlyAbandonsAtEveryStage) {
  // Before COMMAND.
  bus.select(true);
  bus.drain();
  bus.select(false);
  EXPECT_TRUE(bus.drain().empty());
  // Half a COMMAND.
  bus.select(true);
  bus.drain();
  bus.send(0x0C);
  bus.select(false);
  EXPECT_TRUE(bus.drain().empty());
  // COMMAND but no DATA.
  bus.select(true);
  bus.drain();
  bus.send_word(cmd_drive_to);
  bus.send(0x10);
  bus.select(false);
  EXPECT_TRUE(bus.drain().empty());
  EXPECT_EQ(joint.target(), 0);
  // RESPONSE not yet taken: the command ran (atomic), but no STATUS goes out.
  bus.select(true);
  bus.drain();
  bus.send_word(cmd_ping);
  bus.send_word(77);
  bus.select(false);
  EXPECT_FALSE(joint.tx_enabled());
  EXPECT_TRUE(bus.drain().empty());
  EXPECT_EQ(joint.transaction().abandoned_count(), 4u);
  expect_recovers();
}

TEST_F(TransactionTest, SelectHighForeverAfterTheCommandIsNotATimeout) {
  bus.select(true);
  bus.drain();
  bus.send_word(cmd_get_target);
  EXPECT_EQ(bus.drain().size(), 2u);
  uint32_t deadline;
  EXPECT_FALSE(joint.next_deadline_us(&deadline));
  bus.advance(10 * timeout());
  EXPECT_EQ(joint.transaction().state(), State::done);
  bus.select(false);
  const auto status = bus.drain();
  ASSERT_EQ(status.size(), 2u);
  EXPECT_EQ(word_from(status[0], status[1]), 170);
}

TEST_F(TransactionTest, StatusNotTakenInTimeIsDroppedAndTxReleased) {
  bus.select(true);
  bus.drain();
  bus.send_word(cmd_home);
  bus.select(false);
  EXPECT_TRUE(joint.tx_enabled());
  bus.advance(timeout() + 1);
  EXPECT_FALSE(joint.tx_enabled());
  uint8_t b;
  EXPECT_FALSE(joint.next_tx_byte(&b));
  expect_recovers();
}

TEST_F(TransactionTest, SelectRisingAgainDropsAPendingStatusAndStartsOver) {
  bus.select(true);
  bus.drain();
  bus.send_word(cmd_home);
  bus.select(false);
  bus.select(true);
  const auto ready = bus.drain();
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_EQ(word_from(ready[0], ready[1]), 4);
  bus.send_word(cmd_get_joint_number);
  EXPECT_EQ(bus.drain().size(), 2u);
  bus.select(false);
  const auto status = bus.drain();
  ASSERT_EQ(status.size(), 2u);
  EXPECT_EQ(word_from(status[0], status[1]), 180);
}

TEST_F(TransactionTest, BytesForOtherJointsAreIgnored) {
  // While not selected, every byte on the shared master TX is someone else's.
  for (int i = 0; i < 50; ++i) bus.send(static_cast<uint8_t>(i * 37));
  EXPECT_FALSE(joint.tx_enabled());
  EXPECT_TRUE(bus.drain().empty());
  // Even while this joint still sends its STATUS.
  bus.select(true);
  bus.drain();
  bus.send_word(cmd_ping);
  bus.send_word(1);
  bus.drain();
  bus.select(false);
  bus.send_word(cmd_drive_to);
  bus.send_word(3000);
  const auto status = bus.drain();
  ASSERT_EQ(status.size(), 2u);
  EXPECT_EQ(word_from(status[0], status[1]), 100);
  EXPECT_EQ(joint.target(), 0);
}

TEST_F(TransactionTest, RepeatedSelectLevelsAreNotEdges) {
  bus.select(true);
  bus.select(true);
  EXPECT_EQ(bus.drain().size(), 2u);
  bus.send_word(cmd_get_position);
  bus.select(true);
  EXPECT_EQ(bus.drain().size(), 2u);
  bus.select(false);
  bus.select(false);
  EXPECT_EQ(bus.drain().size(), 2u);
  EXPECT_EQ(joint.transaction().state(), State::idle);
}

TEST_F(TransactionTest, TimeoutsWorkAcrossTheMicrosecondWrap) {
  BusHarness wrapping(joint, 9600, 0xFFFFFFFFu - 1000u);
  wrapping.select(true);
  wrapping.drain();  // now past the wrap
  ASSERT_LT(wrapping.now_us(), 0x80000000u);
  wrapping.advance(timeout() - 2500);
  EXPECT_EQ(joint.transaction().state(), State::await_command);
  wrapping.advance(3000);
  EXPECT_EQ(joint.transaction().state(), State::abandoned);
  wrapping.select(false);
  const auto e = wrapping.transact(cmd_ping, int16_t{5});
  EXPECT_EQ(e.status_word(), 100);
}

// Random bytes, edges, silences and ticks: TX is driven only while selected, or while the
// STATUS of a just-finished transaction goes out, and never longer than the timeout after
// select fell. The joint always comes back to serve a clean transaction.
TEST_F(TransactionTest, RandomEventSequencesKeepTxInvariants) {
  std::mt19937 rng(12345);
  testing::EncoderDriver encoder;
  uint32_t now = 0xFFF00000u;
  bool selected = false;
  uint32_t fell_at = 0;
  for (int round = 0; round < 200; ++round) {
    for (int i = 0; i < 300; ++i) {
      const uint32_t r = rng() % 100;
      if (r < 10) {
        selected = !selected;
        if (!selected) fell_at = now;
        joint.on_select(selected, now);
      } else if (r < 60) {
        joint.on_rx_byte(static_cast<uint8_t>(rng()), now);
      } else if (r < 75) {
        uint8_t b;
        const bool enabled = joint.tx_enabled();
        const bool got = joint.next_tx_byte(&b);
        ASSERT_TRUE(!got || enabled);
      } else if (r < 85) {
        encoder.move(joint, static_cast<int32_t>(rng() % 21) - 10);
      } else if (r < 95) {
        joint.control_tick();
      } else {
        now += rng() % 20000;
      }
      now += rng() % 1200;
      joint.poll(now);
      if (joint.tx_enabled()) {
        ASSERT_TRUE(selected || joint.transaction().state() == State::send_status);
        if (!selected) {
          ASSERT_LE(now - fell_at, timeout() + 1200u + 20000u);
        }
      }
      ASSERT_EQ(joint.transaction().selected(), selected);
    }
    if (selected) {
      selected = false;
      joint.on_select(false, now);
    }
    now += timeout() + 1;
    joint.poll(now);
    ASSERT_FALSE(joint.tx_enabled());
    BusHarness bus2(joint, 9600, now);
    const auto e = bus2.transact(cmd_get_joint_number);
    ASSERT_EQ(e.ready_word(), 4);
    ASSERT_EQ(e.response_word(), 4);
    ASSERT_EQ(e.status_word(), 180);
    now = bus2.now_us();
  }
}

}  // namespace
}  // namespace armctl::joint_bus

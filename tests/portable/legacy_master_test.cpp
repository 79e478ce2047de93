// Legacy-master mode on the portable code, against a simulated original Arduino Mega
// master: it hands COMMAND (and DATA) to its UART and lowers select 30 us later, while the
// bytes are still on the wire, then waits up to 50 ms for STATUS, which must be in the
// legacy dialect (command code on success, 93 unknown, 94 bad data). Every command, at
// 9600 and 115200 baud; and a standard-mode joint under that master, for contrast.
#include <gtest/gtest.h>

#include <vector>

#include "joint_bus_harness.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_bus {
namespace {

struct LegacyExchange {
  std::vector<std::uint8_t> ready;
  std::vector<std::uint8_t> after;  // everything the joint sent after select fell (50 ms)
};

// The original master's timing, byte by byte on the simulated clock.
class LegacyMaster {
 public:
  LegacyMaster(JointController& joint, std::uint32_t baud) : joint_(joint), byte_us_(10'000'000u / baud) {}

  LegacyExchange transact(int16_t command, bool with_data, int16_t data) {
    LegacyExchange e;
    joint_.on_select(true, now_);
    e.ready = take_tx(byte_us_ * 2 + 100);
    // COMMAND (+ DATA) handed to the UART at once; select falls 30 us later.
    std::vector<std::uint8_t> out{word_low(command), word_high(command)};
    if (with_data) {
      out.push_back(word_low(data));
      out.push_back(word_high(data));
    }
    const std::uint32_t handed_at = now_;
    step_to(handed_at + 30);
    joint_.on_select(false, now_);
    for (std::size_t i = 0; i < out.size(); ++i) {
      step_to(handed_at + static_cast<std::uint32_t>(i + 1) * byte_us_);
      joint_.on_rx_byte(out[i], now_);
    }
    e.after = take_tx(50'000);  // waits up to 50 ms for RESPONSE/STATUS
    step_to(now_ + 1000);       // the master's own pause before the next transaction
    return e;
  }

 private:
  void step_to(std::uint32_t t) {
    while (now_ < t) {
      now_ = std::min(t, now_ + 10);
      joint_.poll(now_);
    }
  }
  // Bytes the joint transmits within `window_us`, one byte time each.
  std::vector<std::uint8_t> take_tx(std::uint32_t window_us) {
    std::vector<std::uint8_t> got;
    const std::uint32_t until = now_ + window_us;
    while (now_ < until) {
      std::uint8_t b = 0;
      if (joint_.tx_enabled() && joint_.next_tx_byte(&b)) {
        got.push_back(b);
        step_to(now_ + byte_us_);
      } else {
        step_to(now_ + 10);
      }
    }
    return got;
  }

  JointController& joint_;
  std::uint32_t byte_us_;
  std::uint32_t now_ = 1000;
};

std::vector<std::uint8_t> words(std::initializer_list<int16_t> ws) {
  std::vector<std::uint8_t> b;
  for (int16_t w : ws) {
    b.push_back(word_low(w));
    b.push_back(word_high(w));
  }
  return b;
}

class LegacyMasterTest : public ::testing::TestWithParam<std::uint32_t> {
 protected:
  void SetUp() override {
    JointOptions o;
    o.legacy_master = true;
    ASSERT_TRUE(joint.begin(3, default_tuning(), GetParam(), o));
    joint.init_encoder(false, false);
  }
  LegacyExchange run(int16_t command, int16_t data = 0) {
    return master.transact(command, command_shape(command).takes_data, data);
  }
  JointController joint;
  LegacyMaster master{joint, GetParam()};
};

TEST_P(LegacyMasterTest, EveryCommandExecutesAndAnswersInTheLegacyDialect) {
  testing::EncoderDriver encoder;
  encoder.move(joint, 40);  // position 40
  EXPECT_EQ(run(cmd_ping, -1234).after, words({-1234, cmd_ping}));
  EXPECT_EQ(run(cmd_get_joint_number).ready, words({3}));
  EXPECT_EQ(run(cmd_get_joint_number).after, words({3, cmd_get_joint_number}));
  EXPECT_EQ(run(cmd_get_position).after, words({40, cmd_get_position}));
  EXPECT_EQ(run(cmd_drive_to, 700).after, words({cmd_drive_to}));
  EXPECT_EQ(joint.target(), 700);
  EXPECT_EQ(run(cmd_get_target).after, words({700, cmd_get_target}));
  EXPECT_EQ(run(cmd_drive_dist, -100).after, words({cmd_drive_dist}));
  EXPECT_EQ(joint.target(), 600);
  EXPECT_EQ(run(cmd_drive_dist_max, 10).after, words({cmd_drive_dist_max}));
  EXPECT_EQ(joint.target(), 50);
  EXPECT_EQ(run(cmd_set_zone, 20).after, words({cmd_set_zone}));
  EXPECT_EQ(joint.zone(), 20);
  EXPECT_EQ(run(cmd_check_target_reached).after, words({1, cmd_check_target_reached}));
  EXPECT_EQ(run(cmd_set_pid_state, 0).after, words({cmd_set_pid_state}));
  EXPECT_FALSE(joint.loop_enabled());
  EXPECT_EQ(run(cmd_set_pid_state, 1).after, words({cmd_set_pid_state}));
  EXPECT_TRUE(joint.loop_enabled());
  EXPECT_EQ(run(cmd_home).after, words({cmd_home}));
  EXPECT_EQ(joint.position(), 0);
  EXPECT_EQ(run(cmd_read_diagnostic, diagnostic_settings).after,
            words({setting_legacy_master, cmd_read_diagnostic}));
  EXPECT_EQ(run(cmd_clear_faults).after, words({cmd_clear_faults}));
  // Errors: 94 for bad data (nothing changes), 93 for an unknown command (no DATA read).
  EXPECT_EQ(run(cmd_set_pid_state, 7).after, words({legacy_status_bad_data}));
  EXPECT_TRUE(joint.loop_enabled());
  EXPECT_EQ(master.transact(3, false, 0).after, words({legacy_status_unknown_command}));
  EXPECT_EQ(master.transact(93, true, 5).after, words({legacy_status_unknown_command}));
  // Everything after that still works: the unknown command's DATA was not taken as a command.
  EXPECT_EQ(run(cmd_ping, 77).after, words({77, cmd_ping}));
  EXPECT_EQ(joint.transaction().abandoned_count(), 0);
}

TEST_P(LegacyMasterTest, SetSpeedIsTheLegacyZeroTo255Cap) {
  const struct {
    int16_t legacy;
    uint8_t percent;
  } cases[] = {{255, 100}, {128, 50}, {1, 1}, {0, 0}, {254, 100}, {51, 20}};
  for (const auto& c : cases) {
    EXPECT_EQ(run(cmd_set_speed, c.legacy).after, words({cmd_set_speed})) << c.legacy;
    EXPECT_EQ(joint.speed_percent(), c.percent) << c.legacy;
  }
  for (int16_t bad : {int16_t{256}, int16_t{-1}, int16_t{1000}}) {
    EXPECT_EQ(run(cmd_set_speed, bad).after, words({legacy_status_bad_data})) << bad;
    EXPECT_EQ(joint.speed_percent(), 20) << "unchanged after " << bad;
  }
}

TEST_P(LegacyMasterTest, BytesThatNeverComeEndTheTransactionAfterTheWordTimeout) {
  joint.on_select(true, 0);
  std::uint8_t b = 0;
  while (joint.next_tx_byte(&b)) {
  }
  joint.on_select(false, 10);
  joint.on_rx_byte(word_low(cmd_drive_to), 1000);  // half of COMMAND, then silence
  joint.poll(1000 + joint.transaction().timeout_us() + 1);
  EXPECT_EQ(joint.transaction().state(), BusTransaction::State::idle);
  EXPECT_FALSE(joint.tx_enabled());
  EXPECT_EQ(joint.transaction().abandoned_count(), 1);
}

TEST_P(LegacyMasterTest, AStandardJointDropsWhatThisMasterSends) {
  // Why the mode exists: without it the same timing abandons every command.
  JointController standard;
  ASSERT_TRUE(standard.begin(3, default_tuning(), GetParam()));
  LegacyMaster m(standard, GetParam());
  EXPECT_TRUE(m.transact(cmd_drive_to, true, 700).after.empty());
  EXPECT_EQ(standard.target(), 0);
}

INSTANTIATE_TEST_SUITE_P(Baud, LegacyMasterTest, ::testing::Values(9600u, 115200u));

}  // namespace
}  // namespace armctl::joint_bus

// What a board may send ahead of the controller (firmware/board/uart.hpp, uart_send_ahead):
// the first byte of READY as select rises, of STATUS as it falls, of a get_position's
// RESPONSE as its COMMAND completes. Over random event sequences, standard and legacy-master
// joints, each predicted byte must be the first one the controller then queues (or, for a
// COMMAND completed after the timeout, nothing at all: the transaction was abandoned).
#include <gtest/gtest.h>

#include <random>

#include "joint_bus_harness.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_bus {
namespace {

struct Counts {
  int select_predictions = 0;
  int response_predictions = 0;
};

Counts check_predictions(bool legacy, std::uint32_t seed) {
  JointOptions options;
  options.legacy_master = legacy;
  JointController joint;
  EXPECT_TRUE(joint.begin(2, default_tuning(), 115200, options));
  joint.init_encoder(false, false);
  testing::EncoderDriver encoder;
  std::mt19937 rng(seed);
  std::uint32_t now = 0xFFFF0000u;  // across the microsecond wrap
  bool selected = false;
  Counts counts;
  auto drain = [&] {
    std::uint8_t b;
    while (joint.tx_enabled() && joint.next_tx_byte(&b)) {
    }
  };
  for (int i = 0; i < 200000; ++i) {
    drain();  // as the firmware does: every byte it may send goes to the UART at once
    const std::uint32_t r = rng() % 100;
    std::uint8_t predicted = 0;
    if (r < 12) {
      selected = !selected;
      const bool ahead = joint.transaction().first_byte_on_select(selected, &predicted);
      joint.on_select(selected, now);
      if (ahead) {
        ++counts.select_predictions;
        std::uint8_t first = 0;
        EXPECT_TRUE(joint.tx_enabled() && joint.next_tx_byte(&first)) << "nothing queued after a prediction";
        EXPECT_EQ(first, predicted);
      }
    } else if (r < 80) {
      // Mostly words a master would send (get_position, ping with data), some noise.
      const std::uint32_t kind = rng() % 4;
      const std::uint8_t byte = kind == 0 ? std::uint8_t{cmd_get_position}
                                : kind == 1 ? std::uint8_t{0}
                                            : static_cast<std::uint8_t>(rng());
      const bool ahead = joint.response_ahead(byte, &predicted);
      joint.on_rx_byte(byte, now);
      if (ahead) {
        ++counts.response_predictions;
        std::uint8_t first = 0;
        const bool queued = joint.tx_enabled() && joint.next_tx_byte(&first);
        if (queued) {
          EXPECT_EQ(first, predicted);
        } else {
          EXPECT_NE(joint.transaction().state(), BusTransaction::State::done) << "only an abandoned command sends nothing";
        }
      }
    } else if (r < 92) {
      encoder.move(joint, static_cast<std::int32_t>(rng() % 41) - 20);
    } else {
      joint.control_tick();
    }
    now += rng() % 200 + (rng() % 50 == 0 ? 5000u : 0u);
    joint.poll(now);
  }
  return counts;
}

TEST(AnswerAhead, PredictedBytesAreTheOnesTheControllerQueues) {
  const Counts c = check_predictions(false, 7);
  // Both kinds are exercised, not just trivially absent.
  EXPECT_GT(c.select_predictions, 1000);
  EXPECT_GT(c.response_predictions, 100);
}

TEST(AnswerAhead, LegacyMasterJointsToo) {
  const Counts c = check_predictions(true, 11);
  EXPECT_GT(c.select_predictions, 1000);
}

}  // namespace
}  // namespace armctl::joint_bus

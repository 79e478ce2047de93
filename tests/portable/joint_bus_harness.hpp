// Test harness: plays the master's side of the joint bus against one JointController with
// simulated wire timing (10 bit times per byte) and a simulated microsecond clock.
#pragma once

#include <cstdint>
#include <vector>

#include "portable/joint_controller.hpp"

namespace armctl::joint_bus::testing {

struct Exchange {
  std::vector<std::uint8_t> ready;     // bytes the joint sent after select rose
  std::vector<std::uint8_t> response;  // bytes the joint sent after COMMAND/DATA
  std::vector<std::uint8_t> status;    // bytes the joint sent after select fell
  int16_t ready_word() const { return word(ready); }
  int16_t response_word() const { return word(response); }
  int16_t status_word() const { return word(status); }
  static int16_t word(const std::vector<std::uint8_t>& b) {
    return b.size() == 2 ? word_from(b[0], b[1]) : int16_t{-1};
  }
};

class BusHarness {
 public:
  explicit BusHarness(JointController& joint, std::uint32_t baud = 9600, std::uint32_t start_us = 0)
      : joint_(joint), byte_us_(10'000'000u / baud), now_us_(start_us) {}

  std::uint32_t now_us() const { return now_us_; }
  std::uint32_t byte_us() const { return byte_us_; }
  void advance(std::uint32_t us) {
    now_us_ += us;
    joint_.poll(now_us_);
  }
  void select(bool high) {
    joint_.on_select(high, now_us_);
    joint_.poll(now_us_);
  }
  void send(std::uint8_t b) {
    advance(byte_us_);  // the byte is complete at the receiver one byte time later
    joint_.on_rx_byte(b, now_us_);
  }
  void send_word(int16_t w) {
    send(word_low(w));
    send(word_high(w));
  }
  // Everything the joint transmits now, one byte time each; checks TX is enabled for each.
  std::vector<std::uint8_t> drain() {
    std::vector<std::uint8_t> out;
    std::uint8_t b = 0;
    while (joint_.tx_enabled() && joint_.next_tx_byte(&b)) {
      out.push_back(b);
      advance(byte_us_);
    }
    return out;
  }
  // A whole well-behaved transaction.
  Exchange transact(int16_t command, bool with_data, int16_t data = 0) {
    Exchange e;
    select(true);
    e.ready = drain();
    send_word(command);
    if (with_data) send_word(data);
    e.response = drain();
    select(false);
    e.status = drain();
    return e;
  }
  Exchange transact(int16_t command) { return transact(command, command_shape(command).takes_data, 0); }
  Exchange transact(int16_t command, int16_t data) { return transact(command, true, data); }

 private:
  JointController& joint_;
  std::uint32_t byte_us_;
  std::uint32_t now_us_;
};

// Drives the encoder inputs like a real encoder: valid 4x quadrature edges, keeping its own
// phase (the joint's count may be re-zeroed by home, the levels are not).
class EncoderDriver {
 public:
  static void levels(int32_t phase, bool* a, bool* b) {
    static const bool kA[4] = {false, false, true, true};
    static const bool kB[4] = {false, true, true, false};
    const int p = static_cast<int>(((phase % 4) + 4) % 4);
    *a = kA[p];
    *b = kB[p];
  }
  void move(JointController& joint, int32_t clicks) {
    const int32_t step = clicks >= 0 ? 1 : -1;
    for (int32_t i = 0; i != clicks; i += step) {
      phase_ += step;
      bool a = false, b = false;
      levels(phase_, &a, &b);
      joint.on_encoder_edge(a, b);
    }
  }
  int32_t phase() const { return phase_; }

 private:
  int32_t phase_ = 0;
};

}  // namespace armctl::joint_bus::testing

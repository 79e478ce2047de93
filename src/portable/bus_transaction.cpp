#include "portable/bus_transaction.hpp"

#include "portable/joint_bus_codes.hpp"

namespace armctl {
namespace joint_bus {

namespace {
const uint32_t kTimeoutBitTimes = 80;       // 4 words of 2 bytes x 10 bits (8N1)
const uint32_t kTurnaroundUs = 2000;        // the master's own reaction time
}  // namespace

void BusTransaction::begin(int16_t ready_word, uint32_t baud, bool legacy_master,
                           int16_t unknown_status) {
  ready_word_ = ready_word;
  legacy_master_ = legacy_master;
  unknown_status_ = unknown_status;
  if (baud == 0) baud = 1;
  timeout_us_ = kTimeoutBitTimes * UINT32_C(1000000) / baud + kTurnaroundUs;
  state_ = State::idle;
  selected_ = false;
  timeout_armed_ = false;
  tx_head_ = 0;
  tx_count_ = 0;
  have_low_byte_ = false;
}

// arm_timeout and timed_out out of line: inlined at each of their uses they cost the joint
// image flash it does not have (docs/firmware.md "Budgets").
__attribute__((noinline)) void BusTransaction::arm_timeout(uint32_t now_us) {
  last_activity_us_ = now_us;
  timeout_armed_ = true;
}

__attribute__((noinline)) bool BusTransaction::timed_out(uint32_t now_us) const {
  // Signed difference: correct across the uint32 wrap, and an event stamped slightly
  // before the last activity never counts as a timeout.
  return timeout_armed_ &&
         static_cast<int32_t>(now_us - last_activity_us_) > static_cast<int32_t>(timeout_us_);
}

bool BusTransaction::next_deadline_us(uint32_t* when) const {
  if (!timeout_armed_) return false;
  *when = last_activity_us_ + timeout_us_ + 1u;
  return true;
}

void BusTransaction::queue_word(int16_t word) {
  if (tx_count_ == 0) tx_head_ = 0;
  // Capacity 4: READY (possibly not yet taken) + RESPONSE, or STATUS alone.
  if (tx_head_ + tx_count_ + 2u > sizeof(tx_)) return;
  tx_[tx_head_ + tx_count_] = word_low(word);
  tx_[tx_head_ + tx_count_ + 1] = word_high(word);
  tx_count_ = static_cast<uint8_t>(tx_count_ + 2u);
}

void BusTransaction::abandon() {
  tx_count_ = 0;
  tx_head_ = 0;
  have_low_byte_ = false;
  timeout_armed_ = false;
  state_ = selected_ ? State::abandoned : State::idle;
  if (abandoned_count_ != 0xFFFFu) ++abandoned_count_;
}

void BusTransaction::on_select(bool high, uint32_t now_us) {
  if (high == selected_) return;  // a repeated level is not an edge
  selected_ = high;
  if (high) {
    // A new transaction, whatever was going on (a STATUS the master did not wait for is
    // dropped: its select rising again means it moved on).
    tx_count_ = 0;
    tx_head_ = 0;
    have_low_byte_ = false;
    state_ = State::await_command;
    queue_word(ready_word_);
    arm_timeout(now_us);
    return;
  }
  if (state_ == State::done && (tx_count_ == 0 || legacy_master_)) {
    // (Legacy master: it lowers select without waiting for RESPONSE; STATUS follows it.)
    send_status(now_us);
  } else if (legacy_master_ && (state_ == State::await_command || state_ == State::await_data)) {
    // The legacy master lowers select while COMMAND/DATA are still on the wire: keep
    // receiving; the timeout still ends a transaction whose bytes never come.
    arm_timeout(now_us);
  } else if (state_ == State::abandoned) {
    state_ = State::idle;
  } else if (state_ != State::idle && state_ != State::send_status) {
    // Select dropped early (before COMMAND/DATA, or before the RESPONSE was taken).
    abandon();
  }
}

void BusTransaction::send_status(uint32_t now_us) {
  queue_word(status_);
  state_ = State::send_status;
  arm_timeout(now_us);
  if (completed_count_ != 0xFFFFu) ++completed_count_;
}

// Out of line: inlined into the board's main loop it costs flash the firmware needs.
__attribute__((noinline)) BusTransaction::Event BusTransaction::on_rx_byte(uint8_t byte, uint32_t now_us) {
  // Bytes while not selected belong to other joints' transactions (except, for a legacy
  // master, the rest of ours after select fell); bytes after the command is complete are
  // surplus: both are ignored.
  if (state_ != State::await_command && state_ != State::await_data) return Event::none;
  if (!selected_ && !legacy_master_) {
    return Event::none;
  }
  if (timed_out(now_us)) {
    abandon();  // a late byte after a silence that poll() has not seen yet
    return Event::none;
  }
  arm_timeout(now_us);
  if (!have_low_byte_) {
    low_byte_ = byte;
    have_low_byte_ = true;
    return Event::none;
  }
  have_low_byte_ = false;
  const int16_t word = word_from(low_byte_, byte);
  if (state_ == State::await_command) {
    command_ = word;
    data_ = 0;
    const CommandShape shape = command_shape(word);
    if (!shape.known) {
      // No DATA is read for an unknown command: the next bytes are not ours to interpret.
      state_ = State::done;
      timeout_armed_ = false;
      complete(unknown_status_, false, 0);
      return Event::none;
    }
    if (shape.takes_data) {
      state_ = State::await_data;
      return Event::none;
    }
  } else {
    data_ = word;
  }
  state_ = State::done;
  timeout_armed_ = false;  // waiting for select to fall has no timeout: it is not blocking
  status_ = status_no_answer;  // until the owner calls complete()
  return Event::command_ready;
}

void BusTransaction::complete(int16_t status, bool has_response, int16_t response) {
  if (state_ != State::done) return;
  status_ = status;
  if (has_response) queue_word(response);
  // Select already fell (legacy master): RESPONSE and STATUS go out now, back to back.
  if (!selected_) send_status(last_activity_us_);
}

void BusTransaction::poll(uint32_t now_us) {
  if (!timed_out(now_us)) return;
  if (state_ == State::send_status) {
    // The STATUS was not taken in time: give the bus back.
    tx_count_ = 0;
    tx_head_ = 0;
    timeout_armed_ = false;
    state_ = State::idle;
  } else {
    abandon();
  }
}

bool BusTransaction::tx_enabled() const {
  switch (state_) {
    case State::await_command:
    case State::await_data:
    case State::done: return selected_;
    case State::send_status: return tx_count_ != 0;
    default: return false;
  }
}

bool BusTransaction::next_tx_byte(uint8_t* byte) {
  if (tx_count_ == 0 || !tx_enabled()) return false;
  *byte = tx_[tx_head_];
  ++tx_head_;
  --tx_count_;
  if (state_ == State::send_status && tx_count_ == 0) {
    state_ = State::idle;
    timeout_armed_ = false;
  }
  return true;
}

}  // namespace joint_bus
}  // namespace armctl

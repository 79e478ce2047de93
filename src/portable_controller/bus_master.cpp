#include "portable_controller/bus_master.hpp"

#include "portable/joint_bus_codes.hpp"
#include "portable_controller/counting.hpp"

namespace armctl {
namespace controller {

namespace jb = ::armctl::joint_bus;

namespace {
// The joint answers from its main loop: allow 2 ms of turnaround beyond the wire time.
const uint32_t turnaround_us = 2000;
// Wait that long for a joint's reply word beyond the words still on the wire.
const uint8_t margin_words = 2;
// Quiet bus after a failure (in word times): a late STATUS or READY dies out meanwhile.
const uint8_t quiet_words = 4;

// Every call but on_rx_byte() holds the received bytes back while it runs (BusPort::hold_rx).
class Held {
 public:
  explicit Held(BusPort* port) : port_(port), saved_(port->hold_rx()) {}
  ~Held() { port_->release_rx(saved_); }

 private:
  BusPort* port_;
  uint8_t saved_;
};

}  // namespace

void BusMaster::begin(BusPort* port, uint32_t baud) {
  port_ = port;
  Held held(port_);
  word_us_ = 20000000UL / baud;  // 2 bytes x 10 bits
  state_ = State::idle;
  result_ready_ = false;
  current_done_ = false;
  next_queued_ = false;
  quiet_ = false;
}

bool BusMaster::can_start(uint32_t now_us) const {
  if (busy()) return false;  // the common case, without a hold
  Held held(port_);
  return state_ == State::idle && !result_ready_ && (!quiet_ || reached(now_us, quiet_until_us_));
}

void BusMaster::arm(uint32_t now_us, uint8_t words_out) {
  deadline_us_ = time(now_us) + (words_out + 1u + margin_words) * word_us_ + turnaround_us;
  have_low_ = false;
}

namespace {
bool valid_request(uint8_t joint, int16_t command) {
  return jb::command_shape(command).known && joint >= 1 && joint <= jb::max_joints;
}
}  // namespace

bool BusMaster::start(uint8_t joint, int16_t command, int16_t data, uint32_t now_us) {
  Held held(port_);
  if (!valid_request(joint, command) || state_ != State::idle || result_ready_) return false;
  const Request request = {joint, command, data};
  begin_transaction(request, now_us, false);
  return true;
}

void BusMaster::begin_transaction(const Request& request, uint32_t now_us, bool selected) {
  // Select first: the joint's turnaround to READY runs while the rest is set up (nothing
  // received is handled before this returns).
  if (!selected) port_->set_select(request.joint, true);
  quiet_ = false;
  current_ = BusResult{request.joint, request.command, request.data, jb::status_no_answer, 0, false, false};
  const jb::CommandShape shape = jb::command_shape(request.command);
  takes_data_ = shape.takes_data;
  returns_value_ = shape.returns_value;
  state_ = State::await_ready;
  arm(now_us, 0);
}

bool BusMaster::chain(uint8_t joint, int16_t command, int16_t data) {
  Held held(port_);
  if (!valid_request(joint, command) || state_ == State::idle || next_queued_) return false;
  next_ = Request{joint, command, data};
  next_queued_ = true;
  return true;
}

bool BusMaster::unchain() {
  if (!next_queued_) return false;  // the common case, without a hold
  Held held(port_);
  const bool was = next_queued_;
  next_queued_ = false;
  return was;
}

bool BusMaster::take_word(uint8_t byte, int16_t* word) {
  if (!have_low_) {
    low_byte_ = byte;
    have_low_ = true;
    return false;
  }
  have_low_ = false;
  *word = jb::word_from(low_byte_, byte);
  return true;
}

void BusMaster::on_rx_byte(uint8_t byte) {
  // Every use of the time below comes after the port calls the byte sets off.
  time_from_port_ = true;
  on_rx_byte(byte, 0);
  time_from_port_ = false;
}

void BusMaster::on_rx_byte(uint8_t byte, uint32_t now_us) {
  int16_t word = 0;
  switch (state_) {
    case State::idle:
      count_up(stray_bytes_);
      return;
    case State::await_ready:
      if (!take_word(byte, &word)) return;
      if (word != current_.joint) {
        finish(jb::status_wrong_joint, now_us);
        return;
      }
      port_->send_byte(jb::word_low(current_.command));
      port_->send_byte(jb::word_high(current_.command));
      if (takes_data_) {
        port_->send_byte(jb::word_low(current_.data));
        port_->send_byte(jb::word_high(current_.data));
      }
      if (returns_value_) {
        state_ = State::await_response;
        arm(now_us, takes_data_ ? 2 : 1);
      } else {
        // Select falls once COMMAND and DATA have left (BusPort); the STATUS wait counts them.
        port_->set_select(current_.joint, false);
        state_ = State::await_status;
        arm(now_us, takes_data_ ? 2 : 1);
      }
      return;
    case State::await_response:
      if (!take_word(byte, &word)) return;
      port_->set_select(current_.joint, false);
      current_.response = word;
      state_ = State::await_status;
      arm(now_us, 0);
      return;
    case State::await_status:
      if (!take_word(byte, &word)) return;
      if (word == jb::success_status(current_.command) && current_.command == jb::cmd_ping &&
          current_.response != current_.data) {
        finish(jb::status_ping_bad_echo, now_us);
        return;
      }
      finish(word, now_us);
      return;
  }
}

void BusMaster::poll(uint32_t now_us) {
  if (!busy()) return;
  Held held(port_);
  if (state_ == State::idle || !reached(now_us, deadline_us_)) return;
  finish(jb::status_no_answer, now_us);
}

void BusMaster::finish(int16_t status, uint32_t now_us) {
  const bool ok = status == jb::success_status(current_.command);
  const bool chain_now = ok && next_queued_ && !result_ready_;
  // The chained joint's select before anything else: its READY turnaround starts now.
  if (chain_now) port_->set_select(next_.joint, true);
  if (state_ == State::await_ready || state_ == State::await_response)
    port_->set_select(current_.joint, false);
  current_.status = status;
  current_.ok = ok;
  state_ = State::idle;
  next_queued_ = false;
  current_.chained_started = chain_now;
  if (result_ready_) {
    current_done_ = true;  // a chained transaction that ended before the result ahead of it was taken
  } else {
    result_ = current_;
    result_ready_ = true;
  }
  if (chain_now) {
    begin_transaction(next_, now_us, true);
  } else if (!current_.ok) {
    quiet_ = true;
    quiet_until_us_ = time(now_us) + quiet_words * word_us_;
  }
}

bool BusMaster::take_result(BusResult* result) {
  if (!result_ready_) return false;  // the common case, without a hold
  Held held(port_);
  if (!result_ready_) return false;
  *result = result_;
  if (current_done_) {
    result_ = current_;
    current_done_ = false;
  } else {
    result_ready_ = false;
  }
  return true;
}

}  // namespace controller
}  // namespace armctl

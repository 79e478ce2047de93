// The master's side of one joint bus transaction (spec "One transaction"), as a state
// machine that never blocks: start() raises select, received bytes and time drive it, and
// the result is one STATUS word per transaction (the joint's, or the master-side codes
// 910 wrong joint, 920 bad ping echo, 990 no answer). Every wait is bounded by a timeout
// derived from the baud rate; after a failed transaction the master keeps the bus quiet
// for a while so that a late byte cannot be read as the next joint's READY.
// The Linux daemon's blocking master is devices/joint_bus/bus_master.hpp; this one is for
// the arm controller core (portable_controller/controller_core.hpp).
#pragma once

#include <stdint.h>

namespace armctl {
namespace controller {

// What the master needs of the wire. The owner delivers received bytes to on_rx_byte().
class BusPort {
 public:
  // Joint 1..7. Raising takes effect at once; lowering only once every byte queued so far
  // has left the wire (the joint abandons a transaction whose select falls early).
  virtual void set_select(uint8_t joint, bool high) = 0;
  virtual void send_byte(uint8_t byte) = 0;  // queued behind earlier bytes
 protected:
  ~BusPort() {}
};

struct BusResult {
  uint8_t joint;
  int16_t command;
  int16_t data;
  int16_t status;    // success_status(command) when it worked
  int16_t response;  // valid when the command returns a value and it worked
  bool ok;
};

class BusMaster {
 public:
  void begin(BusPort* port, uint32_t baud);

  bool busy() const { return state_ != State::idle; }
  // Idle and the quiet time after a failure has passed.
  bool can_start(uint32_t now_us) const;
  // Starts a transaction; false (nothing done) if busy or the command is not in the table.
  bool start(uint8_t joint, int16_t command, int16_t data, uint32_t now_us);
  void on_rx_byte(uint8_t byte, uint32_t now_us);
  void poll(uint32_t now_us);
  // The result of the transaction that just ended, once: true and *result filled.
  bool take_result(BusResult* result);

  uint32_t word_time_us() const { return word_us_; }
  // A transaction's expected duration (5 words on the wire, and turnaround), for planning.
  uint32_t transaction_estimate_us() const { return 5 * word_us_ + 1000; }
  uint16_t stray_bytes() const { return stray_bytes_; }

 private:
  enum class State : uint8_t { idle, await_ready, await_response, await_status };
  void finish(int16_t status, uint32_t now_us);
  void arm(uint32_t now_us, uint8_t words_out);
  bool take_word(uint8_t byte, int16_t* word);

  BusPort* port_ = nullptr;
  uint32_t word_us_ = 0;
  State state_ = State::idle;
  BusResult current_{};
  bool result_ready_ = false;
  bool returns_value_ = false;
  bool takes_data_ = false;
  uint8_t low_byte_ = 0;
  bool have_low_ = false;
  uint32_t deadline_us_ = 0;
  uint32_t quiet_until_us_ = 0;
  bool quiet_ = false;
  uint16_t stray_bytes_ = 0;
};

}  // namespace controller
}  // namespace armctl

// One joint's side of a joint bus transaction, as a state machine driven by events
// (select edges, received bytes, time). It never blocks, drives TX only while selected
// (or while sending its STATUS right after its own select fell) and returns to Idle from
// any sequence of bytes, edges and silences. It knows the wire format, not the commands:
// when COMMAND (and DATA, if the command takes one) are complete it reports
// command_ready, and the owner executes the command and calls complete().
//
// State table (docs/joint-controller.md has the full version):
//   Idle            --select rises--> AwaitCommand (READY queued)
//   AwaitCommand    --2 bytes--> unknown: complete(930) ; no data: command_ready ;
//                                else AwaitData
//   AwaitData       --2 bytes--> command_ready (owner calls complete())
//   Done            (RESPONSE queued if any) --select falls--> SendStatus (STATUS queued)
//   SendStatus      --STATUS popped or timeout--> Idle
//   any selected state --silence > timeout while waiting for bytes--> Abandoned
//   AwaitCommand/AwaitData/Abandoned, or Done with RESPONSE unsent --select falls--> Idle
//                                                              (no STATUS)
//   Abandoned       (TX released, bytes ignored) --select falls--> Idle
//   SendStatus/Idle --select rises--> AwaitCommand (a pending STATUS is dropped)
//
// Legacy-master mode (begin(..., legacy_master = true); the original Mega master lowers
// select while COMMAND and DATA are still on the wire):
//   AwaitCommand/AwaitData --select falls--> same state, still receiving (the timeout
//                                            bounds it), then command_ready
//   command complete after select fell --complete()--> SendStatus (RESPONSE, then STATUS)
//   Done with RESPONSE unsent --select falls--> SendStatus (rest of RESPONSE, then STATUS)
#pragma once

#include <stdint.h>

#include "portable/joint_bus_codes.hpp"

namespace armctl {
namespace joint_bus {

class BusTransaction {
 public:
  enum class State : uint8_t {
    idle,
    await_command,
    await_data,
    done,
    send_status,
    abandoned,
  };
  enum class Event : uint8_t { none, command_ready };

  // joint_number goes out as READY; baud sets the timeout (see timeout_us()).
  // unknown_status: the STATUS for an unknown command (930, or 93 in the legacy dialect).
  void begin(int16_t ready_word, uint32_t baud, bool legacy_master = false,
             int16_t unknown_status = 930);

  void on_select(bool high, uint32_t now_us);
  Event on_rx_byte(uint8_t byte, uint32_t now_us);
  void poll(uint32_t now_us);
  bool next_tx_byte(uint8_t* byte);
  bool tx_enabled() const;

  // After command_ready: the command and data that were received.
  int16_t command() const { return command_; }
  int16_t data() const { return data_; }
  // Finish the command: queue RESPONSE (if has_response) now and STATUS for when select
  // falls.
  void complete(int16_t status, bool has_response, int16_t response);

  State state() const { return state_; }
  // Whether `byte` completes a COMMAND word equal to `command` while selected (its owner
  // may then answer ahead, see first_byte_on_select; unless the master paused longer than
  // the timeout within that word, when on_rx_byte() abandons the transaction instead).
  bool completes_command(uint8_t byte, int16_t command) const {
    return state_ == State::await_command && have_low_byte_ && selected_ && word_from(low_byte_, byte) == command;
  }
  // Whether the select edge `high` (a change of level) will be answered, and the first
  // byte of the answer: READY as select rises; STATUS as it falls once the command is
  // complete and its RESPONSE taken. A board may send that byte ahead, from its select
  // interrupt (firmware/board/uart.hpp).
  bool first_byte_on_select(bool high, uint8_t* byte) const {
    *byte = static_cast<uint8_t>(high ? ready_word_ : status_);
    return high || (state_ == State::done && tx_count_ == 0 && !legacy_master_);
  }
  bool selected() const { return selected_; }
  // Silence allowed while waiting for COMMAND/DATA bytes and for STATUS to be taken:
  // 4 word times (80 bit times) + 2 ms for the master's turnaround.
  uint32_t timeout_us() const { return timeout_us_; }
  // When poll() next has something to do; false if no timeout is armed.
  bool next_deadline_us(uint32_t* when) const;
  // Counters for diagnostics (saturate at 65535).
  uint16_t abandoned_count() const { return abandoned_count_; }
  uint16_t completed_count() const { return completed_count_; }

 private:
  void abandon();
  void send_status(uint32_t now_us);
  void queue_word(int16_t word);
  void arm_timeout(uint32_t now_us);
  bool timed_out(uint32_t now_us) const;

  uint32_t timeout_us_ = 0;
  uint32_t last_activity_us_ = 0;
  int16_t ready_word_ = 0;
  int16_t command_ = 0;
  int16_t data_ = 0;
  int16_t status_ = 0;
  int16_t unknown_status_ = 930;
  uint8_t tx_[4] = {0, 0, 0, 0};  // at most READY+RESPONSE or RESPONSE+STATUS are pending
  uint8_t tx_head_ = 0;
  uint8_t tx_count_ = 0;
  uint8_t low_byte_ = 0;
  bool have_low_byte_ = false;
  bool selected_ = false;
  bool timeout_armed_ = false;
  bool legacy_master_ = false;
  State state_ = State::idle;
  uint16_t abandoned_count_ = 0;
  uint16_t completed_count_ = 0;
};

}  // namespace joint_bus
}  // namespace armctl

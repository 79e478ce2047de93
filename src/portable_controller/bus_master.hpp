// The master's side of one joint bus transaction (spec "One transaction"), as a state
// machine that never blocks: start() raises select, received bytes and time drive it, and
// the result is one STATUS word per transaction (the joint's, or the master-side codes
// 910 wrong joint, 920 bad ping echo, 990 no answer). Every wait is bounded by a timeout
// derived from the baud rate; after a failed transaction the master keeps the bus quiet
// for a while so that a late byte cannot be read as the next joint's READY.
// One transaction may be queued behind the one under way (chain()): it starts from the
// STATUS itself, so a board that delivers bytes from its receive interrupt (the Mega)
// selects the next joint without a main-loop pass in between.
// The host's blocking master, for armctl driving a joint bus itself, is
// devices/joint_bus/bus_master.hpp; this one is the arm controller core's
// (portable_controller/controller_core.hpp), on the Mega and in the Linux controller.
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
  // An owner that delivers bytes from an interrupt (the Mega's UART1 receive interrupt)
  // masks it here: the master brackets every call made from elsewhere with these, so
  // on_rx_byte() never sees its state half changed. Where bytes are delivered by the
  // thread that calls everything else (Linux), nothing to do.
  virtual uint8_t hold_rx() { return 0; }         // returns what release_rx() restores
  virtual void release_rx(uint8_t /*held*/) {}
  // The time, for an owner that delivers bytes with BusMaster::on_rx_byte(byte) (no time).
  virtual uint32_t now_us() { return 0; }
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
  bool chained_started;  // the transaction chain() queued started as this one ended
};

class BusMaster {
 public:
  void begin(BusPort* port, uint32_t baud);

  // busy(), chained() and result_pending() read one byte each: no hold needed.
  bool busy() const { return state_ != State::idle; }
  // Idle and the quiet time after a failure has passed.
  bool can_start(uint32_t now_us) const;
  // Starts a transaction; false (nothing done) if busy or the command is not in the table.
  bool start(uint8_t joint, int16_t command, int16_t data, uint32_t now_us);
  // The transaction to start the moment the one under way ends well (its STATUS is the
  // success code and its result has room: the one before was taken), from on_rx_byte()
  // itself: no main-loop pass between the STATUS and the next select edge. It is dropped
  // if the one under way fails. False (nothing queued) if idle, one is queued already, or
  // the command is not in the table.
  bool chain(uint8_t joint, int16_t command, int16_t data);
  // Drops the queued transaction if it has not started; false if none was queued.
  bool unchain();
  bool chained() const { return next_queued_; }
  bool result_pending() const { return result_ready_; }
  // The only calls that may come from an interrupt (BusPort::hold_rx). The second reads the
  // time from the port (BusPort::now_us), and only after what the byte sets off (COMMAND
  // sent, select lowered or raised): an interrupt handler's turnaround without its clock.
  void on_rx_byte(uint8_t byte, uint32_t now_us);
  void on_rx_byte(uint8_t byte);
  void poll(uint32_t now_us);
  // The results of the transactions that ended, oldest first, each once: true and *result
  // filled (at most two wait: one, and the chained one that ended before it was taken).
  bool take_result(BusResult* result);

  uint32_t word_time_us() const { return word_us_; }
  // A transaction's expected duration (5 words on the wire, and turnaround), for planning.
  uint32_t transaction_estimate_us() const { return 5 * word_us_ + 1000; }
  uint16_t stray_bytes() const { return stray_bytes_; }

 private:
  enum class State : uint8_t { idle, await_ready, await_response, await_status };
  struct Request {
    uint8_t joint;
    int16_t command;
    int16_t data;
  };
  // `selected`: its select is raised already.
  void begin_transaction(const Request& request, uint32_t now_us, bool selected);
  void finish(int16_t status, uint32_t now_us);
  void arm(uint32_t now_us, uint8_t words_out);
  bool take_word(uint8_t byte, int16_t* word);
  // `given`, or the port's time when the byte came without one (read when first needed).
  uint32_t time(uint32_t given) const { return time_from_port_ ? port_->now_us() : given; }

  BusPort* port_ = nullptr;
  uint32_t word_us_ = 0;
  // Changed by on_rx_byte() (on the Mega from an interrupt), read alone by busy(),
  // result_pending() and chained(): volatile.
  volatile State state_ = State::idle;
  BusResult current_{};
  BusResult result_{};     // the oldest result not taken
  volatile bool result_ready_ = false;
  bool current_done_ = false;  // current_ ended too, behind result_
  Request next_{};
  volatile bool next_queued_ = false;
  bool time_from_port_ = false;  // within on_rx_byte(byte)
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

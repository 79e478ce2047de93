// The joint controller: one joint's side of the joint bus plus its position loop.
// Portable code (C++14, no STL, no heap, no exceptions, no float): the same source runs in
// the ATmega328P firmware (firmware/) and in the host simulator (src/devices/joint_sim).
//
// It never blocks and never does I/O. The board layer (or the simulator) feeds it events
// and carries out what it asks for:
//   bus:     on_select(), on_rx_byte(), poll()  ->  next_tx_byte(), tx_enabled()
//   encoder: on_encoder_edge(a, b) on every edge of A or B
//   control: every 1 ms, either control_tick() (one call), or on the AVR
//            control_sample() with interrupts masked, then control_compute() with
//            interrupts enabled  ->  DriveOutput (PWM duty + H-bridge enable)
//
// Firmware entry point for the 1 ms control step (ATmega328P), so that encoder edges are
// not lost while the loop computes (worst ~1,160 cycles with default tuning, ~1,320 at the
// upper bounds of every tuning field; docs/joint-controller.md "Figures"):
//   ISR(TIMER0_COMPA_vect) {            // interrupts are masked on entry
//     joint.control_sample();           // copies the encoder count: a few cycles
//     TIMSK0 &= ~(1 << OCIE0A);         // this ISR must not nest in itself
//     sei();                            // encoder (and select/UART byte-queue) ISRs may run
//     const DriveOutput out = joint.control_compute();
//     cli(); TIMSK0 |= (1 << OCIE0A);
//     h_bridge_apply(out.duty, out.enable);
//   }
// Rules for that split: while control_compute() runs, interrupts may call
// on_encoder_edge(), on_select(), poll(), next_tx_byte(), tx_enabled() - never
// on_rx_byte() (a command changes loop state), execute(), begin() or the views. A board that
// calls on_rx_byte() from its UART RX ISR must therefore not do so during control_compute():
// keep RXCIE0 off meanwhile (the UART buffers 2 bytes, ~2 ms at 9600 baud), or queue the
// byte for later, as firmware/joint_isrs.cpp does. Running control_tick()
// or the pair from the main loop on a 1 ms flag (bus bytes also handled in the main loop)
// is equally fine: then control_sample()
// (reads the int32 count) needs ATOMIC_BLOCK and control_compute() needs nothing.
//
// Other interrupt rules on the AVR (docs/joint-controller.md, "ISR sharing"): AVR
// interrupts do not nest unless an ISR re-enables them, so calls made from an ISR need
// nothing more. Every call made from the main loop (poll, next_tx_byte, tx_enabled, the
// views, or bus calls if the board polls the UART) must run with interrupts masked
// (ATOMIC_BLOCK), because the encoder ISR writes the 32-bit count, the UART RX ISR (if the
// board uses one for on_rx_byte) changes target/zone/speed/loop state and the transaction,
// and the timer ISR writes the loop state and (with the loop off) the target.
//
// Encoder count and position: the count is int32 (it cannot overflow in practice); the
// position the bus sees is that count saturated to int16, and the loop works on the int32
// count, so a joint pushed beyond +-32767 clicks is driven back rather than wrapped.
#pragma once

#include <stdint.h>

#include "portable/bus_transaction.hpp"
#include "portable/fault_monitor.hpp"
#include "portable/joint_bus_codes.hpp"
#include "portable/joint_options.hpp"
#include "portable/joint_tuning.hpp"
#include "portable/position_loop.hpp"
#include "portable/quadrature_decoder.hpp"

namespace armctl {
namespace joint_bus {

// What executing one command produced (also usable without the bus, e.g. by tests).
struct CommandResult {
  int16_t status;      // 100 + 10 x command, 930 or 940 (the bus maps them to the legacy
                       // dialect in legacy-master mode)
  bool has_response;   // a RESPONSE word goes out before STATUS
  int16_t response;
};

// Counters only the board layer sees (read over the bus with read_diagnostic). The
// simulator leaves them 0 (reset cause: power-on).
struct BoardDiagnostics {
  // In the order of their read_diagnostic indices 1..4 (diagnostic_bus_events_lost ...):
  // bus events lost, encoder edges lost, UART errors, reset cause (MCUSR bits).
  uint8_t counts[4];
};

class JointController {
 public:
  // joint_number 1..7 (EEPROM on the AVR); baud sets the transaction timeouts. Returns
  // false (and the joint then stays silent on the bus, loop off) if joint_number is out of
  // range or baud is 0. Power-up state: position 0, target 0, loop on (holds where it is),
  // speed 100 %, zone 0, no faults. options: motor polarity, legacy-master mode.
  bool begin(uint8_t joint_number, const JointTuning& tuning, uint32_t baud,
             const JointOptions& options = JointOptions());
  // Take the current encoder levels as reference without counting (call once after begin).
  void init_encoder(bool a, bool b) { decoder_.reset(a, b); }

  // Bus events. now_us: free-running microseconds, uint32 that wraps (wrap is handled).
  // Until begin() succeeded these are ignored: an unconfigured joint never drives TX.
  void on_select(bool high, uint32_t now_us) {
    if (configured_) transaction_.on_select(high, now_us);
  }
  void on_rx_byte(uint8_t byte, uint32_t now_us);
  // Whether on_rx_byte(byte, ...) completes a get_position, and *first the first byte of
  // its RESPONSE (the position now): a board may send it ahead, before the command is
  // executed (firmware/board/uart.hpp). Encoder edges must not be applied in between.
  bool response_ahead(uint8_t byte, uint8_t* first) const {
    *first = word_low(position());
    return transaction_.completes_command(byte, cmd_get_position);
  }
  void poll(uint32_t now_us) { transaction_.poll(now_us); }  // timeouts; call often
  bool next_tx_byte(uint8_t* byte) { return transaction_.next_tx_byte(byte); }
  bool tx_enabled() const { return transaction_.tx_enabled(); }
  // When poll() next has work (a timeout); false if none is armed. For event-driven sims.
  bool next_deadline_us(uint32_t* when) const { return transaction_.next_deadline_us(when); }

  // Encoder: call on every edge of A or B with both levels (ISR-safe, a table look-up).
  void on_encoder_edge(bool a, bool b) { decoder_.on_edge(a, b); }

  // Control, once every 1 ms, in one of two forms (docs/joint-controller.md, "ISR sharing"):
  //  * control_tick(): sample and compute in one call (host simulator, tests, or firmware
  //    that accepts the encoder interrupt waiting for the whole computation);
  //  * control_sample() with interrupts masked (a few cycles: copies the int32 encoder
  //    count), then control_compute() with interrupts enabled, so encoder edges are served
  //    during the computation. While control_compute() runs, only on_encoder_edge(),
  //    on_select(), poll(), next_tx_byte() and tx_enabled() may interrupt it; on_rx_byte(),
  //    execute(), begin(), init_encoder() and the views must not (they touch or read loop
  //    state that the computation writes).
  DriveOutput control_tick() {
    control_sample();
    return control_compute();
  }
  void control_sample() { sampled_count_ = decoder_.count(); }
  DriveOutput control_compute();

  // Run one command against the joint state (what the bus does once COMMAND/DATA are in).
  // set_speed takes 0..100 (%); in legacy-master mode the bus hands it the legacy 0..255.
  CommandResult execute(int16_t command, int16_t data);

  // Faults (fault_* bits): raised by the control step, held until clear_faults: the bridge
  // brakes for fault_brake_ticks (enabled, duty 0: motor shorted), then is off; the target
  // follows the position and drive commands are refused with 940.
  static const uint16_t fault_brake_ticks = 500;
  int16_t faults() const { return faults_; }
  bool braking() const { return faults_ != 0 && brake_ticks_ != 0; }
  // The board's own counters, for read_diagnostic (call from the main loop, masked).
  void set_board_diagnostics(const BoardDiagnostics& d) { board_ = d; }
  const JointOptions& options() const { return options_; }
  // One read_diagnostic word (index 0..diagnostic_count-1, joint_bus_codes.hpp).
  int16_t diagnostic(int16_t index) const;

  // Read-only views for tests, simulator and firmware (no side effects).
  bool configured() const { return configured_; }
  uint8_t joint_number() const { return joint_number_; }
  int16_t position() const;  // get_position's answer
  int32_t encoder_count() const { return decoder_.count(); }
  uint16_t encoder_errors() const { return decoder_.errors(); }
  int16_t target() const { return loop_.target(); }
  bool loop_enabled() const { return loop_.enabled(); }
  uint8_t speed_percent() const { return loop_.speed_percent(); }
  int16_t zone() const { return loop_.zone(); }
  bool target_reached() const { return loop_.target_reached(decoder_.count()); }
  int32_t setpoint_q8() const { return loop_.ramp().setpoint_q8(); }
  int32_t setpoint_velocity_q8() const { return loop_.ramp().velocity_q8(); }
  int32_t integral_q16() const { return loop_.pid().integral_q16(); }
  DriveOutput last_output() const { return last_output_; }
  const BusTransaction& transaction() const { return transaction_; }
  const PositionLoop& loop() const { return loop_; }

 private:
  QuadratureDecoder decoder_;
  int32_t sampled_count_ = 0;  // the count control_compute() works on
  PositionLoop loop_;
  BusTransaction transaction_;
  FaultMonitor monitor_;
  BoardDiagnostics board_ = BoardDiagnostics{{0, 0, 0, 0}};
  uint8_t settings_ = 0;  // setting_* bits, from the options
  JointOptions options_;
  DriveOutput last_output_ = DriveOutput{0, false};
  int16_t faults_ = 0;
  uint16_t brake_ticks_ = 0;  // ticks of braking left after a fault was raised
  uint8_t joint_number_ = 0;
  bool configured_ = false;
};

}  // namespace joint_bus
}  // namespace armctl

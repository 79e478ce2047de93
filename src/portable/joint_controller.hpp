// The joint controller: one joint's side of the joint bus plus its position loop.
// Portable code (C++14, no STL, no heap, no exceptions, no float): the same source runs in
// the ATmega328P firmware (firmware/) and in the host simulator (src/devices/joint_sim).
//
// It never blocks and never does I/O. The board layer (or the simulator) feeds it events
// and carries out what it asks for:
//   bus:     on_select(), on_rx_byte(), poll()  ->  next_tx_byte(), tx_enabled()
//   encoder: on_encoder_edge(a, b) on every edge of A or B
//   control: control_tick() every 1 ms  ->  DriveOutput (PWM duty + H-bridge enable)
//
// Interrupt rules on the AVR (docs/joint-controller.md, "ISR sharing"): AVR interrupts do
// not nest, so calls made from an ISR need nothing more. Every call made from the main loop
// (poll, next_tx_byte, tx_enabled, the views, or bus calls if the board polls the UART)
// must run with interrupts masked (ATOMIC_BLOCK), because the encoder ISR writes the 32-bit
// count, the UART RX ISR changes target/zone/speed/loop state and the transaction, and the
// timer ISR writes the loop state and (with the loop off) the target.
//
// Encoder count and position: the count is int32 (it cannot overflow in practice); the
// position the bus sees is that count saturated to int16, and the loop works on the int32
// count, so a joint pushed beyond +-32767 clicks is driven back rather than wrapped.
#pragma once

#include <stdint.h>

#include "portable/bus_transaction.hpp"
#include "portable/joint_bus_codes.hpp"
#include "portable/joint_tuning.hpp"
#include "portable/position_loop.hpp"
#include "portable/quadrature_decoder.hpp"

namespace armctl {
namespace joint_bus {

// What executing one command produced (also usable without the bus, e.g. by tests).
struct CommandResult {
  int16_t status;      // 100 + 10 x command, 930 or 940
  bool has_response;   // a RESPONSE word goes out before STATUS
  int16_t response;
};

class JointController {
 public:
  // joint_number 1..7 (EEPROM on the AVR); baud sets the transaction timeouts. Returns
  // false (and the joint then stays silent on the bus, loop off) if joint_number is out of
  // range or baud is 0. Power-up state: position 0, target 0, loop on (holds where it is),
  // speed 100 %, zone 0.
  bool begin(uint8_t joint_number, const JointTuning& tuning, uint32_t baud);
  // Take the current encoder levels as reference without counting (call once after begin).
  void init_encoder(bool a, bool b) { decoder_.reset(a, b); }

  // Bus events. now_us: free-running microseconds, uint32 that wraps (wrap is handled).
  // Until begin() succeeded these are ignored: an unconfigured joint never drives TX.
  void on_select(bool high, uint32_t now_us) {
    if (configured_) transaction_.on_select(high, now_us);
  }
  void on_rx_byte(uint8_t byte, uint32_t now_us);
  void poll(uint32_t now_us) { transaction_.poll(now_us); }  // timeouts; call often
  bool next_tx_byte(uint8_t* byte) { return transaction_.next_tx_byte(byte); }
  bool tx_enabled() const { return transaction_.tx_enabled(); }
  // When poll() next has work (a timeout); false if none is armed. For event-driven sims.
  bool next_deadline_us(uint32_t* when) const { return transaction_.next_deadline_us(when); }

  // Encoder: call on every edge of A or B with both levels (ISR-safe, a table look-up).
  void on_encoder_edge(bool a, bool b) { decoder_.on_edge(a, b); }

  // Control: call exactly every 1 ms. Returns what the H-bridge should do.
  DriveOutput control_tick();

  // Run one command against the joint state (what the bus does once COMMAND/DATA are in).
  CommandResult execute(int16_t command, int16_t data);

  // Read-only views for tests, simulator and firmware (no side effects).
  bool configured() const { return configured_; }
  uint8_t joint_number() const { return joint_number_; }
  int16_t position() const { return saturate_to_int16(decoder_.count()); }
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
  PositionLoop loop_;
  BusTransaction transaction_;
  DriveOutput last_output_ = DriveOutput{0, false};
  uint8_t joint_number_ = 0;
  bool configured_ = false;
};

}  // namespace joint_bus
}  // namespace armctl

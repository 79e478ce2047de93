// Something attached to the simulated joint bus: one joint controller with its select line,
// its RX (wired to the master's TX) and its TX (diode-OR'ed onto the master's RX).
//
// Implementations: SimJoint (the portable JointController + the motor model, sim_joint.hpp)
// and the emulated ATmega328P running the real firmware (devices/joint_avr). The bus
// (sim_bus.hpp) owns simulated time and calls an endpoint in strictly non-decreasing time:
//
//   advance_to(t)            run everything internal (control ticks, physics, firmware
//                            cycles) up to t. Called before any event at t.
//   on_select(high, t)       the joint's select line changed at t.
//   on_rx_byte(byte, t)      a byte finished arriving on the joint's RX at t (stop bit end).
//   next_tx_byte(t)          the joint's TX is idle at t: the byte it sends next, if any, and
//                            when it was handed to the UART (at or before t: an emulated chip
//                            runs ahead of the bus between polls). The bus puts it on the wire
//                            from then (not before the previous byte's stop bit) for 10 bit
//                            times; it asks again when that byte's stop bit ends.
//   tx_enabled()             the joint drives its TX line (it may be idle-high while doing
//                            so). Two joints doing this at once is bus contention.
//   next_event_time()        the earliest time after the last advance_to() at which the
//                            endpoint could start a byte or change tx_enabled() on its own
//                            (next control tick, a transaction timeout, a firmware byte being
//                            shifted out). The bus never lets time pass that point without
//                            calling advance_to() and next_tx_byte() there. Returning a time
//                            too early only costs speed; too late delays the joint's answers.
//                            TimePoint::max() means "nothing until the next bus event" (e.g.
//                            not selected and TX released): the bus then advances the
//                            endpoint lazily, which is what makes long idle runs cheap.
#pragma once

#include <cstdint>
#include <optional>

#include "core/clock.hpp"

namespace armctl::joint_sim {

// A byte a joint sends, and when its UART was given it.
struct TxByte {
  std::uint8_t value;
  TimePoint written;
};

class BusEndpoint {
 public:
  virtual ~BusEndpoint() = default;

  virtual void advance_to(TimePoint t) = 0;
  virtual void on_select(bool high, TimePoint t) = 0;
  virtual void on_rx_byte(std::uint8_t byte, TimePoint t) = 0;
  virtual std::optional<TxByte> next_tx_byte(TimePoint t) = 0;
  virtual bool tx_enabled() const = 0;
  virtual TimePoint next_event_time() const = 0;
};

}  // namespace armctl::joint_sim

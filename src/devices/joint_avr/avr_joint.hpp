// One joint on the simulated joint bus made of real firmware on an emulated ATmega328P
// (AvrChip) driving the simulated motor, gearbox and encoder (joint_sim::JointHardware):
// the same BusEndpoint as the portable-code SimJoint, so the bus master cannot tell them
// apart except by timing.
//
// Coupling, every `hardware.step` (50 us by default) of simulated time:
//   motor model -> encoder edges, each applied to PD2/PD3 at its own cycle (INT0/INT1)
//   chip runs to the end of the step -> H-bridge inputs read from the timer registers and
//   port pins (OC1B/OC2A duty, D4 enable) -> motor model drive for the next step.
// Bus: select -> PB4 (PCINT4); a received byte -> UART RXC at its stop-bit end; a byte the
// firmware writes to UDR0 starts on the wire at that cycle (or when the previous one ends),
// although the bus looks for it only every few microseconds.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "devices/joint_avr/avr_chip.hpp"
#include "devices/joint_sim/bus_endpoint.hpp"
#include "devices/joint_sim/joint_hardware.hpp"

namespace armctl::joint_avr {

// Latency statistics in CPU cycles.
struct LatencyStats {
  std::uint64_t count = 0;
  std::uint64_t max_cycles = 0;
  std::uint64_t total_cycles = 0;  // for the mean
  void add(std::uint64_t cycles) {
    ++count;
    total_cycles += cycles;
    if (cycles > max_cycles) max_cycles = cycles;
  }
};

struct AvrJointSetup {
  std::string elf_path;
  std::vector<std::uint8_t> eeprom;  // joint_eeprom_image(...) or a deliberately bad one
  joint_sim::JointHardwareParams hardware;
};

class AvrJoint final : public joint_sim::BusEndpoint, private joint_sim::EncoderEdgeSink {
 public:
  explicit AvrJoint(const AvrJointSetup& setup, TimePoint start = TimePoint{});

  // BusEndpoint
  void advance_to(TimePoint t) override;
  void on_select(bool high, TimePoint t) override;
  void on_rx_byte(std::uint8_t byte, TimePoint t) override;
  std::optional<joint_sim::TxByte> next_tx_byte(TimePoint t) override;
  bool tx_enabled() const override;
  TimePoint next_event_time() const override;

  TimePoint time() const { return now_; }
  AvrChip& chip() { return *chip_; }
  const AvrChip& chip() const { return *chip_; }
  const joint_sim::JointHardware& hardware() const { return hardware_; }
  // Hold the chip in reset (it never answers, all its pins high-Z) or let it run again.
  void set_held_in_reset(bool held) { chip_->set_held_in_reset(held); }
  // An obstacle: the joint cannot leave min..max clicks from now on (tests: a joint
  // blocked mid-move).
  void set_obstacle(joint_sim::EndStops stops) { hardware_.set_end_stops(stops); }

  // Last command byte in (RXC) -> first reply byte out (UDR0 write).
  const LatencyStats& rx_to_tx() const { return rx_to_tx_; }
  // Select rise -> first READY byte out; select fall -> first STATUS byte out.
  const LatencyStats& select_rise_to_tx() const { return select_rise_to_tx_; }
  const LatencyStats& select_fall_to_tx() const { return select_fall_to_tx_; }
  // Bytes the firmware wrote while two were already waiting for the wire (the UART holds
  // one in UDR0 and one in the shift register: a third would be lost on real hardware).
  std::uint64_t tx_overruns() const { return tx_overruns_; }

  std::uint64_t cycle_at(TimePoint t) const;
  TimePoint time_at(std::uint64_t cycle) const;

 private:
  enum class LastBusEvent { none, rx, select_rise, select_fall };
  struct QueuedByte {
    std::uint8_t value;
    std::uint64_t cycle;
  };
  void on_encoder_edge(bool a, bool b, TimePoint t) override;
  void on_uart_output(std::uint8_t byte, std::uint64_t cycle);
  void apply_drive();

  std::unique_ptr<AvrChip> chip_;
  joint_sim::JointHardware hardware_;
  TimePoint start_;
  TimePoint now_;
  TimePoint last_bus_event_;
  bool select_high_ = false;
  bool encoder_a_ = false;
  bool encoder_b_ = false;
  std::deque<QueuedByte> tx_queue_;
  LastBusEvent last_event_ = LastBusEvent::none;
  std::uint64_t last_event_cycle_ = 0;
  LatencyStats rx_to_tx_;
  LatencyStats select_rise_to_tx_;
  LatencyStats select_fall_to_tx_;
  std::uint64_t tx_overruns_ = 0;
};

}  // namespace armctl::joint_avr

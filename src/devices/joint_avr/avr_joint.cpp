#include "devices/joint_avr/avr_joint.hpp"

#include <algorithm>


namespace armctl::joint_avr {
namespace {

// While a transaction may be under way the bus looks at the chip this often: the firmware
// answers a few microseconds after an event, and a byte it starts is found at most this
// late (0.6 bit times at 115200 baud); it goes on the wire from the cycle it was written.
constexpr Duration bus_poll_quantum = std::chrono::microseconds(5);
// After any bus event the chip counts as busy this long (it may still reply).
constexpr Duration busy_after_bus_event = std::chrono::milliseconds(2);

// Pin numbers on the board (firmware/board/pins.hpp).
constexpr int select_bit = 4;     // PB4 = D12
constexpr int encoder_a_bit = 2;  // PD2 = D2 (INT0)
constexpr int encoder_b_bit = 3;  // PD3 = D3 (INT1)
}  // namespace

AvrJoint::AvrJoint(const AvrJointSetup& setup, TimePoint start)
    : chip_(std::make_unique<AvrChip>(setup.elf_path)),
      hardware_(setup.hardware, start),
      start_(start),
      now_(start),
      last_bus_event_(start) {
  chip_->write_eeprom(0, setup.eeprom);
  chip_->set_uart_output([this](std::uint8_t b, std::uint64_t c) { on_uart_output(b, c); });
  encoder_a_ = hardware_.encoder_a();
  encoder_b_ = hardware_.encoder_b();
  chip_->drive_pin('D', encoder_a_bit, encoder_a_);
  chip_->drive_pin('D', encoder_b_bit, encoder_b_);
  chip_->drive_pin('B', select_bit, false);
}

std::uint64_t AvrJoint::cycle_at(TimePoint t) const {
  const auto ns = (t - start_).count();
  return ns <= 0 ? 0 : static_cast<std::uint64_t>(ns) * 2 / 125;  // 16 cycles per 1000 ns
}

TimePoint AvrJoint::time_at(std::uint64_t cycle) const {
  return start_ + Duration{static_cast<std::int64_t>(cycle * 125 / 2)};
}

void AvrJoint::on_encoder_edge(bool a, bool b, TimePoint t) {
  chip_->run_to_cycle(cycle_at(t));
  if (a != encoder_a_) chip_->drive_pin('D', encoder_a_bit, a);
  if (b != encoder_b_) chip_->drive_pin('D', encoder_b_bit, b);
  encoder_a_ = a;
  encoder_b_ = b;
}

void AvrJoint::apply_drive() {
  const BridgeInputs in = chip_->bridge_inputs();
  // Both inputs high brakes just like both low: the motor sees their difference. "Right"
  // (D11) positive: the original boards' wiring (JointHardwareParams::leads_swapped).
  hardware_.set_drive_fraction(in.right - in.left, in.enable);
}

void AvrJoint::advance_to(TimePoint t) {
  const Duration step = hardware_.params().step;
  while (now_ < t) {
    const TimePoint next = std::min(t, now_ + step);
    hardware_.advance_to(next, this);
    chip_->run_to_cycle(cycle_at(next));
    apply_drive();
    now_ = next;
  }
}

void AvrJoint::on_select(bool high, TimePoint t) {
  advance_to(t);
  select_high_ = high;
  last_bus_event_ = t;
  last_event_ = high ? LastBusEvent::select_rise : LastBusEvent::select_fall;
  last_event_cycle_ = chip_->cycle();
  chip_->drive_pin('B', select_bit, high);
}

void AvrJoint::on_rx_byte(std::uint8_t byte, TimePoint t) {
  advance_to(t);
  last_bus_event_ = t;
  last_event_ = LastBusEvent::rx;
  last_event_cycle_ = chip_->cycle();
  chip_->uart_receive(byte);
}

void AvrJoint::on_uart_output(std::uint8_t byte, std::uint64_t cycle) {
  if (tx_queue_.size() >= 2) ++tx_overruns_;
  tx_queue_.push_back(QueuedByte{byte, cycle});
  const std::uint64_t latency = cycle - last_event_cycle_;
  switch (last_event_) {
    case LastBusEvent::rx: rx_to_tx_.add(latency); break;
    case LastBusEvent::select_rise: select_rise_to_tx_.add(latency); break;
    case LastBusEvent::select_fall: select_fall_to_tx_.add(latency); break;
    case LastBusEvent::none: break;
  }
  last_event_ = LastBusEvent::none;  // only the first byte after an event is a turnaround
}

std::optional<joint_sim::TxByte> AvrJoint::next_tx_byte(TimePoint t) {
  advance_to(t);
  if (tx_queue_.empty()) return std::nullopt;
  const QueuedByte b = tx_queue_.front();
  tx_queue_.pop_front();
  return joint_sim::TxByte{b.value, time_at(b.cycle)};
}

bool AvrJoint::tx_enabled() const {
  // The transmitter drives the line (idle high) while TXEN0 is set, and a real UART keeps
  // shifting out what it was given even after TXEN0 is cleared.
  return chip_->uart_transmitter_enabled() || !tx_queue_.empty();
}

TimePoint AvrJoint::next_event_time() const {
  if (!tx_queue_.empty()) return std::max(now_, time_at(tx_queue_.front().cycle));
  if (chip_->held_in_reset()) return TimePoint::max();
  const bool busy = select_high_ || chip_->uart_transmitter_enabled() ||
                    now_ - last_bus_event_ < busy_after_bus_event;
  return busy ? now_ + bus_poll_quantum : TimePoint::max();
}

}  // namespace armctl::joint_avr

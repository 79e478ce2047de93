#include "devices/joint_avr/avr_mega_arm.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "devices/joint_avr/atmega328p.hpp"

namespace armctl::joint_avr {

namespace {
// Idle bus: the Mega and the joints advance this far per step.
constexpr Duration kIdleStep = std::chrono::microseconds(250);
// The Mega's UART1 and the joints' UARTs run at the same real rate (both are 16 MHz AVRs).
AvrArmOptions on_avr_wire(AvrArmOptions options) {
  options.wire_at_avr_rate = true;
  return options;
}
// A byte time after the last bus activity the bus counts as active still (STATUS follows
// a select fall after the joint's turnaround).
constexpr int kActiveWords = 8;
}  // namespace

std::string default_mega_firmware_elf() { return ARMCTL_MEGA_FIRMWARE_ELF; }
std::string mega_firmware_elf_115200() { return ARMCTL_MEGA_FIRMWARE_ELF_115200; }
std::string mega_firmware_elf_battery() { return ARMCTL_MEGA_FIRMWARE_ELF_BATTERY; }

AvrMegaArm::AvrMegaArm(joint_sim::ArmConfig config, std::string mega_elf, std::uint32_t upstream_baud,
                       AvrArmOptions joints)
    : arm_(std::move(config), on_avr_wire(std::move(joints))),
      mega_(std::make_unique<AvrChip>(mega_elf, atmega2560_model)),
      upstream_baud_(upstream_baud),
      start_(arm_.now()),
      upstream_byte_time_(wire_time(1, upstream_baud)),
      short_step_(std::max<Duration>(std::chrono::microseconds(5), wire_time(1, arm_.config().baud) / 4)) {
  if (upstream_baud == 0) throw ArmctlError(ErrorKind::invalid_argument, "AvrMegaArm: upstream baud must be > 0");
  mega_->set_uart_output(
      [this](std::uint8_t byte, std::uint64_t cycle) { events_.push_back(BusEvent{cycle, 0, false, byte}); }, 1);
  mega_->set_uart_output(
      [this](std::uint8_t byte, std::uint64_t cycle) {
        // Starts on the wire at the write (or when the byte before it has gone).
        const TimePoint begins = std::max(time_at(cycle), from_mega_free_at_);
        from_mega_free_at_ = begins + upstream_byte_time_;
        from_mega_.push_back(UpstreamByte{byte, from_mega_free_at_});
      },
      0);
  mega_->watch_output_port('A', [this](int bit, bool level, std::uint64_t cycle) {
    if (bit < 7) events_.push_back(BusEvent{cycle, bit + 1, level, 0});
  });
  last_bus_activity_ = start_;
}

std::uint64_t AvrMegaArm::cycle_at(TimePoint t) const {
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t - start_).count();
  return static_cast<std::uint64_t>(ns) * atmega328p::clock_hz / 1'000'000'000u;
}

TimePoint AvrMegaArm::time_at(std::uint64_t cycle) const {
  return start_ + std::chrono::nanoseconds(cycle * 1'000'000'000u / atmega328p::clock_hz);
}

void AvrMegaArm::send_upstream(std::span<const std::uint8_t> bytes) {
  for (std::uint8_t b : bytes) {
    const TimePoint begins = std::max(now(), upstream_free_at_);
    upstream_free_at_ = begins + upstream_byte_time_;
    to_mega_.push_back(UpstreamByte{b, upstream_free_at_});
  }
}

std::vector<UpstreamByte> AvrMegaArm::take_upstream() {
  std::vector<UpstreamByte> out;
  while (!from_mega_.empty() && from_mega_.front().at <= now()) {
    out.push_back(from_mega_.front());
    from_mega_.pop_front();
  }
  return out;
}

void AvrMegaArm::reset_mega() {
  mega_->reset();
  joint_sim::SimBus& bus = arm_.bus();
  for (int joint = 1; joint <= 7; ++joint) {
    const auto bit = static_cast<std::uint8_t>(1u << (joint - 1));
    if ((selects_ & bit) == 0) continue;
    selects_ = static_cast<std::uint8_t>(selects_ & ~bit);
    ++select_edges_;
    if (joint <= bus.joint_count()) bus.set_select(joint, false);
  }
}

bool AvrMegaArm::bus_active() {
  return selects_ != 0 || arm_.bus().master_tx_busy() ||
         now() - last_bus_activity_ < wire_time(2 * kActiveWords, arm_.config().baud);
}

void AvrMegaArm::run_until(TimePoint t) {
  while (now() < t) {
    TimePoint end = std::min(t, now() + (bus_active() ? short_step_ : kIdleStep));
    if (!to_mega_.empty()) end = std::min(end, std::max(now(), to_mega_.front().at));
    // A joint's byte already on the wire ends at a known instant, whatever the Mega does
    // meanwhile: the step ends there, so the Mega gets it when its stop bit ends.
    const TimePoint byte_in = arm_.bus().next_byte_to_master();
    if (byte_in > now()) end = std::min(end, byte_in);
    step(end);
  }
}

void AvrMegaArm::step(TimePoint end) {
  while (!to_mega_.empty() && to_mega_.front().at <= now()) {
    mega_->uart_receive(to_mega_.front().value, 0);
    to_mega_.pop_front();
  }
  events_.clear();
  mega_->run_to_cycle(cycle_at(end));
  joint_sim::SimBus& bus = arm_.bus();
  for (const BusEvent& e : events_) {
    const TimePoint at = std::clamp(time_at(e.cycle), now(), end);
    if (at > now()) bus.run_until(at);
    last_bus_activity_ = at;
    if (e.joint == 0) {
      if (trace_) trace_(BusTraceEvent{BusTraceEvent::Kind::master_byte, 0, at});
      const std::uint8_t b = e.byte;
      bus.write(std::span<const std::uint8_t>(&b, 1));
      continue;
    }
    const auto bit = static_cast<std::uint8_t>(1u << (e.joint - 1));
    const bool was = (selects_ & bit) != 0;
    if (was == e.level) continue;
    selects_ = static_cast<std::uint8_t>(e.level ? selects_ | bit : selects_ & ~bit);
    ++select_edges_;
    if (trace_)
      trace_(BusTraceEvent{e.level ? BusTraceEvent::Kind::select_rise : BusTraceEvent::Kind::select_fall, e.joint, at});
    if (e.joint <= bus.joint_count()) bus.set_select(e.joint, e.level);
  }
  if (end > now()) bus.run_until(end);
  while (bus.rx_available() > 0) {
    const auto b = bus.read_byte(now());
    if (!b) break;
    last_bus_activity_ = now();
    if (trace_) trace_(BusTraceEvent{BusTraceEvent::Kind::joint_byte, 0, now()});
    mega_->uart_receive(*b, 1);
  }
}

}  // namespace armctl::joint_avr

#include "devices/joint_sim/sim_joint.hpp"

#include <string>

#include "core/error.hpp"

namespace armctl::joint_sim {

SimJoint::SimJoint(std::uint8_t joint_number, const joint_bus::JointTuning& tuning,
                   std::uint32_t baud, const JointHardwareParams& hardware, TimePoint start,
                   const joint_bus::JointOptions& options)
    : hardware_(hardware, start), now_(start), next_tick_(start + control_period) {
  if (!controller_.begin(joint_number, tuning, baud, options)) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "simulated joint: joint number " + std::to_string(joint_number) +
                          " or baud " + std::to_string(baud) +
                          " refused (allowed: joint 1..7, baud > 0)");
  }
  controller_.init_encoder(hardware_.encoder_a(), hardware_.encoder_b());
  controller_.set_board_diagnostics(joint_bus::BoardDiagnostics{{0, 0, 0, 1}});  // power-on reset
}

std::uint32_t SimJoint::micros(TimePoint t) {
  // Free-running microsecond counter that wraps like the AVR's (the controller handles it).
  return static_cast<std::uint32_t>(
      static_cast<std::uint64_t>(t.time_since_epoch().count() / 1000));
}

bool SimJoint::turn_by_hand(double clicks) {
  if (controller_.loop_enabled()) return false;
  hardware_.turn_by_hand(clicks, this);
  return true;
}

void SimJoint::on_encoder_edge(bool a, bool b, TimePoint /*t*/) {
  controller_.on_encoder_edge(a, b);
}

void SimJoint::advance_to(TimePoint t) {
  if (t < now_) return;
  while (next_tick_ <= t) {
    hardware_.advance_to(next_tick_, this);
    now_ = next_tick_;
    controller_.poll(micros(now_));
    const joint_bus::DriveOutput out = controller_.control_tick();
    hardware_.set_drive(out.duty, out.enable);
    next_tick_ += control_period;
  }
  hardware_.advance_to(t, this);
  now_ = t;
  controller_.poll(micros(now_));
}

void SimJoint::on_select(bool high, TimePoint t) {
  advance_to(t);
  controller_.on_select(high, micros(t));
}

void SimJoint::on_rx_byte(std::uint8_t byte, TimePoint t) {
  advance_to(t);
  controller_.on_rx_byte(byte, micros(t));
}

std::optional<TxByte> SimJoint::next_tx_byte(TimePoint t) {
  advance_to(t);
  std::uint8_t b = 0;
  if (controller_.next_tx_byte(&b)) return TxByte{b, t};
  return std::nullopt;
}

TimePoint SimJoint::next_event_time() const {
  // Only a transaction timeout changes what the joint does on the bus without a bus event;
  // control ticks and physics run lazily inside advance_to().
  std::uint32_t when = 0;
  if (!controller_.next_deadline_us(&when)) return TimePoint::max();
  const std::uint32_t ahead = when - micros(now_);  // modular: deadlines lie ahead
  if (ahead > 0x80000000u) return now_;             // already due
  return now_ + std::chrono::microseconds(ahead);
}

}  // namespace armctl::joint_sim

// One simulated joint on the simulated bus: the portable JointController (the same code
// the firmware runs) driving the simulated motor, gearbox and encoder (JointHardware).
// The control loop ticks every 1 ms of simulated time; encoder edges reach the controller
// in order before each tick and before every bus event.
#pragma once

#include <cstdint>

#include "devices/joint_sim/bus_endpoint.hpp"
#include "devices/joint_sim/joint_hardware.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_sim {

inline constexpr Duration control_period = std::chrono::milliseconds(1);

class SimJoint final : public BusEndpoint, private EncoderEdgeSink {
 public:
  // Throws ArmctlError(invalid_argument) if the controller refuses joint_number or baud.
  SimJoint(std::uint8_t joint_number, const joint_bus::JointTuning& tuning, std::uint32_t baud,
           const JointHardwareParams& hardware, TimePoint start = TimePoint{},
           const joint_bus::JointOptions& options = {});

  // BusEndpoint
  void advance_to(TimePoint t) override;
  void on_select(bool high, TimePoint t) override;
  void on_rx_byte(std::uint8_t byte, TimePoint t) override;
  std::optional<TxByte> next_tx_byte(TimePoint t) override;
  bool tx_enabled() const override { return controller_.tx_enabled(); }
  TimePoint next_event_time() const override;

  TimePoint time() const { return now_; }
  const joint_bus::JointController& controller() const { return controller_; }
  // Direct access for tests that bypass the bus (e.g. to run one command).
  joint_bus::JointController& controller() { return controller_; }
  const JointHardware& hardware() const { return hardware_; }
  JointHardware& hardware() { return hardware_; }
  // A hand turning the joint by `clicks` (teach tests); refused (false) while the position
  // loop is on: a joint under control would fight the hand.
  bool turn_by_hand(double clicks);

 private:
  void on_encoder_edge(bool a, bool b, TimePoint t) override;
  static std::uint32_t micros(TimePoint t);

  joint_bus::JointController controller_;
  JointHardware hardware_;
  TimePoint now_;
  TimePoint next_tick_;
};

}  // namespace armctl::joint_sim

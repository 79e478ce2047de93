// The simulated SCARA arm with real firmware: every joint of an ArmConfig is the joint
// firmware ELF on an emulated ATmega328P (AvrJoint) driving the same motor model as
// joint_sim::SimArm, all on one joint_sim::SimBus. The bus master talks to link() exactly
// as it talks to SimArm. Test tool only (libsimavr is GPL; docs/firmware.md).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "devices/joint_avr/avr_joint.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "devices/joint_sim/sim_bus.hpp"
#include "portable/joint_options.hpp"

namespace armctl::joint_avr {

struct AvrArmOptions {
  std::string elf_path;  // empty: the ELF this build produced (default_firmware_elf())
  // EEPROM image per select line (1..7) instead of the one made from the config: a board
  // set to another joint number, an erased EEPROM, a bad check byte.
  std::map<int, std::vector<std::uint8_t>> eeprom_overrides;
  // Write each joint's tuning from the config into its EEPROM tuning block (so the
  // firmware runs the same gains as the portable-code simulation).
  bool write_tuning = true;
  // Motor polarity and legacy-master mode written into every joint's EEPROM (settings byte).
  joint_bus::JointOptions joints{};
  // The wire carries bytes at the rate the emulated UARTs make them (avr_byte_time), not at
  // the nominal baud. Needed when the master is an emulated AVR too (AvrMegaArm): it lowers
  // select when its own UART says the last byte has left, which on a wire 2 % slower (at
  // 115200) is before the joint has that byte, and the joint then drops the command.
  bool wire_at_avr_rate = false;
};

// How long a 16 MHz AVR UART in double speed (U2X, as both firmwares set it) takes for one
// 8N1 byte at `baud`: 1040 us at 9600 (9615 baud), 85 us at 115200 (117,647 baud).
Duration avr_byte_time(std::uint32_t baud);

// The firmware ELF built by this CMake build (ARMCTL_FIRMWARE_ELF).
std::string default_firmware_elf();

class AvrArm {
 public:
  // The config's baud must be 9600 or 115200 (what the firmware supports).
  explicit AvrArm(joint_sim::ArmConfig config, AvrArmOptions options = {});

  AvrArm(const AvrArm&) = delete;
  AvrArm& operator=(const AvrArm&) = delete;

  transport::JointBusLink& link() { return *bus_; }
  joint_sim::SimBus& bus() { return *bus_; }
  const joint_sim::ArmConfig& config() const { return config_; }

  TimePoint now() const { return bus_->now(); }
  void run_until(TimePoint t) { bus_->run_until(t); }
  void advance(Duration d) { bus_->advance(d); }

  int joint_count() const { return static_cast<int>(joints_.size()); }
  // Joint on select line `number`, brought up to now. Throws invalid_argument if absent.
  AvrJoint& joint(int number);

 private:
  joint_sim::ArmConfig config_;
  std::vector<std::unique_ptr<AvrJoint>> joints_;  // index = line - 1 (null if absent)
  std::unique_ptr<joint_sim::SimBus> bus_;
};

}  // namespace armctl::joint_avr

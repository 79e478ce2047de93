#include "devices/joint_avr/avr_arm.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "devices/joint_avr/eeprom_image.hpp"

namespace armctl::joint_avr {

std::string default_firmware_elf() { return ARMCTL_FIRMWARE_ELF; }

Duration avr_byte_time(std::uint32_t baud) {
  // UBRR as the firmwares round it (firmware/board/uart.cpp); 8 cycles a bit with U2X.
  const std::uint64_t ubrr = (16'000'000ULL + 4ULL * baud) / (8ULL * baud) - 1;
  const std::uint64_t cycles = 10 * 8 * (ubrr + 1);
  return std::chrono::nanoseconds(cycles * 1000 / 16);
}

AvrArm::AvrArm(joint_sim::ArmConfig config, AvrArmOptions options) : config_(std::move(config)) {
  const std::string elf = options.elf_path.empty() ? default_firmware_elf() : options.elf_path;
  int lines = 0;
  for (const joint_sim::JointConfig& j : config_.joints) lines = std::max(lines, int(j.number));
  joints_.resize(static_cast<std::size_t>(lines));
  std::vector<joint_sim::BusEndpoint*> endpoints(static_cast<std::size_t>(lines), nullptr);
  for (const joint_sim::JointConfig& j : config_.joints) {
    AvrJointSetup setup;
    setup.elf_path = elf;
    setup.hardware = j.hardware;
    const auto override_it = options.eeprom_overrides.find(j.number);
    if (override_it != options.eeprom_overrides.end()) {
      setup.eeprom = override_it->second;
    } else {
      std::optional<joint_bus::JointTuning> tuning;
      if (options.write_tuning) tuning = j.tuning;
      setup.eeprom = joint_eeprom_image(j.number, config_.baud, tuning, options.joints);
    }
    auto joint = std::make_unique<AvrJoint>(setup);
    endpoints[j.number - 1u] = joint.get();
    joints_[j.number - 1u] = std::move(joint);
  }
  bus_ = std::make_unique<joint_sim::SimBus>(config_.baud, std::move(endpoints),
                                             options.wire_at_avr_rate ? avr_byte_time(config_.baud) : Duration::zero());
}

AvrJoint& AvrArm::joint(int number) {
  if (number < 1 || number > joint_count() || !joints_[std::size_t(number - 1)]) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "emulated arm: no joint " + std::to_string(number) + " (allowed: 1.." +
                          std::to_string(joint_count()) + ")");
  }
  bus_->sync();
  return *joints_[std::size_t(number - 1)];
}

}  // namespace armctl::joint_avr

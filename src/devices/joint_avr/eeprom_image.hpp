// The joint controller's EEPROM contents, as firmware/board/joint_config.hpp lays them out
// (and as firmware/tools/joint_eeprom.sh writes them for avrdude): 4 configuration bytes at
// address 0, an optional 24-byte tuning block at address 16.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "portable/joint_options.hpp"
#include "portable/joint_tuning.hpp"

namespace armctl::joint_avr {

inline constexpr std::uint16_t eeprom_size = 1024;
inline constexpr std::uint16_t eeprom_tuning_address = 16;

// Joint 1..7 and baud 9600 or 115200 (ArmctlError(invalid_argument) otherwise); options:
// motor polarity and legacy-master mode (settings byte, firmware/board/joint_config.hpp).
// The rest of the 1 KiB is 0xFF (erased), except the tuning block if given.
std::vector<std::uint8_t> joint_eeprom_image(std::uint8_t joint, std::uint32_t baud,
                                             const std::optional<joint_bus::JointTuning>& tuning,
                                             const joint_bus::JointOptions& options = {});

// A raw image for tests of bad EEPROM: 4 configuration bytes as given, rest erased.
std::vector<std::uint8_t> raw_eeprom_image(std::uint8_t magic, std::uint8_t joint,
                                           std::uint8_t baud_code, std::uint8_t check);

inline std::vector<std::uint8_t> erased_eeprom_image() {
  return std::vector<std::uint8_t>(eeprom_size, 0xFF);
}

}  // namespace armctl::joint_avr

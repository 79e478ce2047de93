#include "board/joint_config.hpp"

#include <avr/eeprom.h>
#include <string.h>

#include "portable/joint_bus_codes.hpp"

namespace board {

bool joint_config_decode(const uint8_t bytes[joint_config_size], JointConfig* config) {
  const uint8_t magic = bytes[0];
  const uint8_t joint = bytes[1];
  const uint8_t settings = bytes[2];
  if (magic != joint_config_magic) return false;
  if (bytes[3] != joint_config_check(joint, settings)) return false;
  if (joint < 1 || joint > armctl::joint_bus::max_joints) return false;
  if (settings > (joint_setting_fast_baud | joint_setting_reversed | joint_setting_legacy_master)) return false;
  config->joint_number = joint;
  config->baud = (settings & joint_setting_fast_baud) ? 115200UL : 9600UL;
  config->options.polarity = (settings & joint_setting_reversed) ? armctl::joint_bus::MotorPolarity::reversed
                                                                 : armctl::joint_bus::MotorPolarity::original;
  config->options.legacy_master = (settings & joint_setting_legacy_master) != 0;
  return true;
}

bool joint_config_load(JointConfig* config) {
  uint8_t bytes[joint_config_size];
  eeprom_read_block(bytes, reinterpret_cast<const void*>(0), joint_config_size);
  return joint_config_decode(bytes, config);
}

}  // namespace board

namespace board {

// The block's fields are the JointTuning fields in order, little-endian like the AVR, and
// avr-gcc aligns nothing: the struct is the block, copied in one go (no per-field code).
static_assert(sizeof(armctl::joint_bus::JointTuning) == joint_tuning_size - 2,
              "JointTuning must be the 22 bytes of the EEPROM tuning block");

bool joint_tuning_decode(const uint8_t bytes[joint_tuning_size],
                         armctl::joint_bus::JointTuning* tuning) {
  if (bytes[0] != joint_tuning_magic) return false;
  uint8_t check = 0xFF;
  for (uint8_t i = 0; i < joint_tuning_size - 1; ++i) check ^= bytes[i];
  if (check != bytes[joint_tuning_size - 1]) return false;
  memcpy(tuning, bytes + 1, sizeof *tuning);
  // begin() clamps every field into its documented range, so no further check is needed.
  return true;
}

armctl::joint_bus::JointTuning joint_tuning_load() {
  uint8_t bytes[joint_tuning_size];
  eeprom_read_block(bytes, reinterpret_cast<const void*>(joint_tuning_address), joint_tuning_size);
  armctl::joint_bus::JointTuning tuning;
  if (!joint_tuning_decode(bytes, &tuning)) tuning = armctl::joint_bus::default_tuning();
  return tuning;
}

}  // namespace board

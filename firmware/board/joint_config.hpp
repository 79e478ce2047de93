// The per-board settings in EEPROM, so one firmware image serves all seven joints.
//
// Layout (4 bytes at EEPROM address 0; tools/joint_eeprom.sh writes it):
//   0: magic       0x4A ('J')
//   1: joint       1..7
//   2: baud code   0 = 9600, 1 = 115200
//   3: check       0xFF ^ magic ^ joint ^ baud code
// An erased EEPROM (all 0xFF) or any mismatch is "not configured": the joint never answers
// on the bus, keeps the motor off and blinks the LED (docs/firmware.md).
//
// Optional tuning block (24 bytes at EEPROM address 16), so a board's loop gains can be set
// without a new image; absent or invalid = the portable default_tuning():
//   16: magic 0x54 ('T')
//   17..36: max_speed_cps, max_accel_cps2, kp_q8, ki_q8, kd_q8 (int32, little-endian)
//   37..38: pwm_max (int16, little-endian)
//   39: check = 0xFF ^ XOR of bytes 16..38
#pragma once

#include <stdint.h>

#include "portable/joint_tuning.hpp"

namespace board {

const uint8_t joint_config_magic = 0x4A;
const uint8_t joint_config_size = 4;

struct JointConfig {
  uint8_t joint_number;  // 1..7
  uint32_t baud;         // 9600 or 115200
};

inline uint8_t joint_config_check(uint8_t joint, uint8_t baud_code) {
  return static_cast<uint8_t>(0xFF ^ joint_config_magic ^ joint ^ baud_code);
}

// Decodes the 4 bytes; false if they are not a valid configuration.
bool joint_config_decode(const uint8_t bytes[joint_config_size], JointConfig* config);
// Reads EEPROM address 0..3 and decodes it.
bool joint_config_load(JointConfig* config);

const uint8_t joint_tuning_address = 16;
const uint8_t joint_tuning_magic = 0x54;
const uint8_t joint_tuning_size = 24;

// Decodes a tuning block; false if it is not valid (then use default_tuning()).
bool joint_tuning_decode(const uint8_t bytes[joint_tuning_size],
                         armctl::joint_bus::JointTuning* tuning);
// The tuning block in EEPROM, or default_tuning() if there is none.
armctl::joint_bus::JointTuning joint_tuning_load();

}  // namespace board

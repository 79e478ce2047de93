// The per-board settings in EEPROM, so one firmware image serves all seven joints.
//
// Layout (4 bytes at EEPROM address 0; tools/joint_eeprom.sh writes it):
//   0: magic       0x4A ('J')
//   1: joint       1..7
//   2: settings    bit 0: baud (0 = 9600, 1 = 115200)
//                  bit 1: motor polarity (0 = original wiring, 1 = reversed; MOTOR_POLARITY=)
//                  bit 2: legacy-master mode (DIALECT=legacy); other bits must be 0
//   3: check       0xFF ^ magic ^ joint ^ settings
// (Images written before the polarity and dialect bits existed read as original polarity,
// standard master.)
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

#include "portable/joint_options.hpp"
#include "portable/joint_tuning.hpp"

namespace board {

const uint8_t joint_config_magic = 0x4A;
const uint8_t joint_config_size = 4;

const uint8_t joint_setting_fast_baud = 1;
const uint8_t joint_setting_reversed = 2;
const uint8_t joint_setting_legacy_master = 4;

struct JointConfig {
  uint8_t joint_number;  // 1..7
  uint32_t baud;         // 9600 or 115200
  armctl::joint_bus::JointOptions options;
};

inline uint8_t joint_config_check(uint8_t joint, uint8_t settings) {
  return static_cast<uint8_t>(0xFF ^ joint_config_magic ^ joint ^ settings);
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

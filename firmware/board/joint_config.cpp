#include "board/joint_config.hpp"

#include <avr/eeprom.h>

#include "portable/joint_bus_codes.hpp"

namespace board {

bool joint_config_decode(const uint8_t bytes[joint_config_size], JointConfig* config) {
  const uint8_t magic = bytes[0];
  const uint8_t joint = bytes[1];
  const uint8_t baud_code = bytes[2];
  if (magic != joint_config_magic) return false;
  if (bytes[3] != joint_config_check(joint, baud_code)) return false;
  if (joint < 1 || joint > armctl::joint_bus::max_joints) return false;
  if (baud_code > 1) return false;
  config->joint_number = joint;
  config->baud = baud_code == 0 ? 9600UL : 115200UL;
  return true;
}

bool joint_config_load(JointConfig* config) {
  uint8_t bytes[joint_config_size];
  eeprom_read_block(bytes, reinterpret_cast<const void*>(0), joint_config_size);
  return joint_config_decode(bytes, config);
}

}  // namespace board

namespace board {
namespace {
int32_t read_int32_le(const uint8_t* p) {
  return static_cast<int32_t>(static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
                              (static_cast<uint32_t>(p[2]) << 16) |
                              (static_cast<uint32_t>(p[3]) << 24));
}
}  // namespace

bool joint_tuning_decode(const uint8_t bytes[joint_tuning_size],
                         armctl::joint_bus::JointTuning* tuning) {
  if (bytes[0] != joint_tuning_magic) return false;
  uint8_t check = 0xFF;
  for (uint8_t i = 0; i < joint_tuning_size - 1; ++i) check ^= bytes[i];
  if (check != bytes[joint_tuning_size - 1]) return false;
  tuning->max_speed_cps = read_int32_le(bytes + 1);
  tuning->max_accel_cps2 = read_int32_le(bytes + 5);
  tuning->kp_q8 = read_int32_le(bytes + 9);
  tuning->ki_q8 = read_int32_le(bytes + 13);
  tuning->kd_q8 = read_int32_le(bytes + 17);
  tuning->pwm_max = static_cast<int16_t>(static_cast<uint16_t>(bytes[21]) |
                                         (static_cast<uint16_t>(bytes[22]) << 8));
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

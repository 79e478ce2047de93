// Robot Commands CMD bytes (spec robot-commands.md) for the portable board side; the
// host's typed view of the same codes is protocol/robot_commands/command_codes.hpp.
#pragma once

#include <stdint.h>

namespace armctl {
namespace controller {

const uint8_t rc_multi_servo_move = 3;
const uint8_t rc_group_download = 5;
const uint8_t rc_group_run = 6;
const uint8_t rc_group_stop = 7;
const uint8_t rc_group_erase = 8;
const uint8_t rc_group_speed = 11;
const uint8_t rc_get_battery_voltage = 15;
const uint8_t rc_multi_servo_off = 20;
const uint8_t rc_servo_position_read = 21;
const uint8_t rc_servo_offset_write = 22;
const uint8_t rc_servo_offset_read = 23;
const uint8_t rc_servo_offset_adjust = 24;
const uint8_t rc_servo_speed = 26;
const uint8_t rc_bus_servo_info_write = 27;
const uint8_t rc_bus_servo_info_read = 28;
// armctl extensions, not in the xArm protocol (an xArm board ignores them as unknown): a
// joint's fault state and diagnostic words, and clear_faults sent to a joint
// (docs/mega-controller.md "Joint faults").
const uint8_t rc_joint_fault_read = 40;
const uint8_t rc_joint_fault_clear = 41;

const uint16_t rc_null_position = 0xFF00;  // MultiServoMove: leave this servo alone
const uint16_t rc_max_position = 1000;
const uint16_t rc_max_move_ms = 30000;
const int16_t rc_max_offset = 125;      // ServoOffsetAdjust: -125..125 position units
const int16_t rc_max_motor_speed = 1000;  // ServoSpeed motor mode: -1000..1000
// BusServoInfoWrite ranges (spec "Units and ranges").
const uint16_t rc_min_millivolts = 4500;
const uint16_t rc_max_millivolts = 12000;
const uint16_t rc_min_temp_max = 50;
const uint16_t rc_max_temp_max = 100;
const uint8_t rc_max_led_warning = 7;  // bit0 overheat, bit1 overvoltage, bit2 overposition

inline uint16_t rc_u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }

// `n` entries {servo u8, position u16} (MultiServoMove, a stored action) into two arrays.
inline void rc_read_targets(const uint8_t* entries, uint8_t n, uint8_t* servos, uint16_t* positions) {
  for (uint8_t k = 0; k < n; ++k) {
    servos[k] = entries[3 * k];
    positions[k] = rc_u16(entries + 1 + 3 * k);
  }
}

}  // namespace controller
}  // namespace armctl

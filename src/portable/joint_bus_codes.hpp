// Joint bus constants shared by the joint controller (firmware and simulator) and the bus
// master. Spec: ../shared/spec/joint-bus.md. C++14, no STL: builds with avr-gcc 5.4.
#pragma once

#include <stdint.h>

namespace armctl {
namespace joint_bus {

enum Command : int16_t {
  cmd_ping = 0,
  cmd_home = 1,
  cmd_set_pid_state = 2,
  cmd_get_position = 6,
  cmd_get_target = 7,
  cmd_get_joint_number = 8,  // the seed's get_slave_num
  cmd_drive_dist = 10,
  cmd_drive_dist_max = 11,
  cmd_drive_to = 12,
  cmd_set_speed = 15,
  cmd_set_zone = 16,
  cmd_check_target_reached = 20,
  // Extensions outside the seed's codes (docs/joint-controller.md "Faults and diagnostics").
  // The original firmware answers both as unknown (93), so a master can tell it apart.
  cmd_read_diagnostic = 40,  // DATA: which word (diagnostic_*); RESPONSE: that word
  cmd_clear_faults = 41,     // faults := 0; the joint holds where it is, bridge on again
};

// The words read_diagnostic returns, by index (DATA). Counters saturate at their maximum.
enum Diagnostic : int16_t {
  diagnostic_faults = 0,              // fault_* bits held until clear_faults
  diagnostic_bus_events_lost = 1,     // board: bus event queue overflows
  diagnostic_encoder_edges_lost = 2,  // board: encoder edges lost (queue full) + decoder
                                      // errors (both channels changed at once)
  diagnostic_uart_errors = 3,         // board: framing / overrun errors
  diagnostic_reset_cause = 4,         // board: MCUSR at the last reset (1 power-on, 2 external,
                                      // 4 brown-out, 8 watchdog)
  diagnostic_abandoned = 5,           // transactions abandoned (timeouts, early select drop)
  diagnostic_settings = 6,            // setting_* bits: how this joint was flashed
  diagnostic_count = 7,
};

// Fault bits (diagnostic_faults). Any of them keeps the H-bridge off until clear_faults.
const int16_t fault_runaway = 1;          // error grew while the loop drove against it
const int16_t fault_following_error = 2;  // joint too far behind its setpoint for too long

// Settings bits (diagnostic_settings).
const int16_t setting_motor_reversed = 1;  // MOTOR_POLARITY=reversed
const int16_t setting_legacy_master = 2;   // DIALECT=legacy (legacy-master mode)

// STATUS words of the legacy dialect (the original firmware): the command code on success.
const int16_t legacy_status_unknown_command = 93;
const int16_t legacy_status_bad_data = 94;

enum StatusCode : int16_t {
  status_no_error = 0,
  status_command_offset = 100,  // success = 100 + 10 x command
  status_wrong_joint = 910,     // master side: READY was not the selected joint's number
  status_ping_bad_echo = 920,   // master side
  status_unknown_command = 930,
  status_bad_data = 940,
  status_no_answer = 990,       // master side: the seed's default_value
};

const uint8_t max_joints = 7;

inline int16_t success_status(int16_t command) {
  return static_cast<int16_t>(status_command_offset + 10 * command);
}

// Shape of each command on the wire.
struct CommandShape {
  bool known;
  bool takes_data;
  bool returns_value;
};

inline CommandShape command_shape(int16_t command) {
  switch (command) {
    case cmd_ping: return CommandShape{true, true, true};
    case cmd_home: return CommandShape{true, false, false};
    case cmd_set_pid_state: return CommandShape{true, true, false};
    case cmd_get_position:
    case cmd_get_target:
    case cmd_get_joint_number:
    case cmd_check_target_reached: return CommandShape{true, false, true};
    case cmd_read_diagnostic: return CommandShape{true, true, true};
    case cmd_clear_faults: return CommandShape{true, false, false};
    case cmd_drive_dist:
    case cmd_drive_dist_max:
    case cmd_drive_to:
    case cmd_set_speed:
    case cmd_set_zone: return CommandShape{true, true, false};
    default: return CommandShape{false, false, false};
  }
}

// Words are 16-bit two's complement, low byte first.
inline uint8_t word_low(int16_t w) { return static_cast<uint8_t>(static_cast<uint16_t>(w) & 0xFFu); }
inline uint8_t word_high(int16_t w) { return static_cast<uint8_t>(static_cast<uint16_t>(w) >> 8); }
inline int16_t word_from(uint8_t low, uint8_t high) {
  return static_cast<int16_t>(static_cast<uint16_t>(low | (static_cast<uint16_t>(high) << 8)));
}

}  // namespace joint_bus
}  // namespace armctl

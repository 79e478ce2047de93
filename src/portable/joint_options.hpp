// How a board was flashed, beyond its joint number and baud: the motor polarity and the
// bus master it answers to. EEPROM on the AVR (firmware/board/joint_config.hpp, `make flash
// ... MOTOR_POLARITY= DIALECT=`); per joint in the simulator. Readable over the bus
// (read_diagnostic, diagnostic_settings).
#pragma once

#include <stdint.h>

namespace armctl {
namespace joint_bus {

enum class MotorPolarity : uint8_t {
  // The original firmware's wiring: to count the encoder up (target above position) drive
  // the H-bridge's "right" input D11 (OC2A); to count down drive "left" D10 (OC1B).
  original = 0,
  // Motor leads (or encoder channels) the other way round: up = D10, down = D11.
  reversed = 1,
};

struct JointOptions {
  MotorPolarity polarity = MotorPolarity::original;
  // Legacy-master mode, for a bus still run by the original Arduino Mega master: COMMAND
  // and DATA are still received after select falls (bounded by the word timeout), STATUS
  // is the legacy dialect (command code on success, 93 unknown, 94 bad data) and
  // set_speed takes the legacy 0..255.
  bool legacy_master = false;
};

}  // namespace joint_bus
}  // namespace armctl

// The status LED on D13 (PB5): lit during a transaction; a blink code when the joint
// number in EEPROM is missing or invalid (docs/firmware.md).
#pragma once

#include <avr/io.h>

#include "board/pins.hpp"

namespace board {

inline void status_led_begin() {
  PORTB &= static_cast<uint8_t>(~_BV(led_bit));
  DDRB |= _BV(led_bit);
}

inline void status_led_set(bool on) {
  if (on) {
    PORTB |= _BV(led_bit);
  } else {
    PORTB &= static_cast<uint8_t>(~_BV(led_bit));
  }
}

}  // namespace board

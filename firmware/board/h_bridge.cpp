#include "board/h_bridge.hpp"

#include <avr/io.h>

#include "board/pins.hpp"

namespace board {
namespace {
const uint8_t duty_full = 255;

uint8_t clamp_magnitude(int16_t duty) {
  const int16_t magnitude = duty < 0 ? static_cast<int16_t>(-duty) : duty;
  return magnitude > duty_full ? duty_full : static_cast<uint8_t>(magnitude);
}

void set_left(uint8_t duty) {
  if (duty == 0) {
    TCCR1A &= static_cast<uint8_t>(~(_BV(COM1B1) | _BV(COM1B0)));  // port drives LOW
  } else {
    OCR1B = duty;
    TCCR1A |= _BV(COM1B1);  // non-inverting: HIGH for duty/255 of the period
  }
}

void set_right(uint8_t duty) {
  if (duty == 0) {
    TCCR2A &= static_cast<uint8_t>(~(_BV(COM2A1) | _BV(COM2A0)));
  } else {
    OCR2A = duty;
    TCCR2A |= _BV(COM2A1);
  }
}
}  // namespace

void h_bridge_safe_state() {
  PORTD &= static_cast<uint8_t>(~_BV(bridge_enable_bit));
  set_left(0);
  set_right(0);
}

void h_bridge_begin() {
  // The pins are already outputs driven LOW: board_safe_state_at_reset (.init3) did that.
  OCR1B = 0;
  OCR2A = 0;
  TCCR1A = _BV(WGM10);  // phase-correct PWM, 8-bit (TOP 0xFF), outputs disconnected
  TCCR1B = _BV(CS10);   // no prescaler
  TCCR2A = _BV(WGM20);  // phase-correct PWM, TOP 0xFF, outputs disconnected
  TCCR2B = _BV(CS20);
}

void h_bridge_apply(int16_t duty, bool enable) {
  if (!enable) {
    h_bridge_safe_state();
    return;
  }
  const uint8_t magnitude = clamp_magnitude(duty);
  // Release the side that must be off before driving the other: never both HIGH.
  if (duty >= 0) {
    set_left(0);
    set_right(magnitude);
  } else {
    set_right(0);
    set_left(magnitude);
  }
  PORTD |= _BV(bridge_enable_bit);
}

}  // namespace board

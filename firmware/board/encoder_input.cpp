#include "board/encoder_input.hpp"

#include <avr/io.h>

#include "board/pins.hpp"

namespace board {

static_assert(encoder_a_bit == 2 && encoder_b_bit == 3, "encoder_levels() assumes PD2/PD3");

void encoder_input_begin() {
  DDRD &= static_cast<uint8_t>(~(_BV(encoder_a_bit) | _BV(encoder_b_bit)));
  // Pull-ups: open-collector encoders work without external resistors.
  PORTD |= _BV(encoder_a_bit) | _BV(encoder_b_bit);
  EICRA = _BV(ISC10) | _BV(ISC00);  // any logical change on INT1 and INT0
  EIFR = _BV(INTF1) | _BV(INTF0);
  EIMSK = _BV(INT1) | _BV(INT0);
}

}  // namespace board

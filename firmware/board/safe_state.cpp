// The very first code after reset (.init3, before static constructors and main): clear the
// reset cause, stop a watchdog that survived the reset, and drive the motor outputs to the
// safe state (H-bridge enable LOW, both PWM inputs LOW). From reset until here (a few
// microseconds) every pin is a high-Z input: the board must pull D4 down (docs/firmware.md).
#include <avr/io.h>
#include <avr/wdt.h>

#include "board/pins.hpp"
#include "board/reset_cause.hpp"

// .noinit survives the C runtime start-up, so main() can still see why the chip reset.
uint8_t board_reset_cause __attribute__((section(".noinit")));

extern "C" void board_safe_state_at_reset(void) __attribute__((naked, used, section(".init3")));

extern "C" void board_safe_state_at_reset(void) {
  board_reset_cause = MCUSR;
  // WDRF must be cleared before WDE can be; otherwise a watchdog reset loops forever.
  MCUSR = 0;
  wdt_disable();
  PORTD &= static_cast<uint8_t>(~_BV(board::bridge_enable_bit));
  DDRD |= _BV(board::bridge_enable_bit);
  PORTB &= static_cast<uint8_t>(~(_BV(board::bridge_left_bit) | _BV(board::bridge_right_bit)));
  DDRB |= _BV(board::bridge_left_bit) | _BV(board::bridge_right_bit);
}

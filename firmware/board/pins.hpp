// Joint controller pinout (Arduino Nano, ATmega328P). Fixed by the boards already built:
// see ../shared/spec/joint-bus.md "Wiring" and docs/firmware.md.
#pragma once

#include <avr/io.h>

namespace board {

// Select line from the master, active HIGH: D12 = PB4 = PCINT4 (pin-change group 0).
const uint8_t select_bit = PB4;
// Encoder channel A D2 = PD2 = INT0, channel B D3 = PD3 = INT1.
const uint8_t encoder_a_bit = PD2;
const uint8_t encoder_b_bit = PD3;
// H-bridge inputs: "left" D10 = PB2 = OC1B, "right" D11 = PB3 = OC2A; enable D4 = PD4.
const uint8_t bridge_left_bit = PB2;
const uint8_t bridge_right_bit = PB3;
const uint8_t bridge_enable_bit = PD4;
// Status LED D13 = PB5.
const uint8_t led_bit = PB5;
// UART TX0 = PD1 (released to high-Z while this joint may not drive the bus).
const uint8_t uart_tx_bit = PD1;

}  // namespace board

// The H-bridge: "left" input D10 (OC1B), "right" input D11 (OC2A), enable D4.
// Timer1 (8-bit phase-correct) and Timer2 (phase-correct), no prescaler: both PWM outputs
// run at 16 MHz / 510 = 31.4 kHz, above hearing and within common bridges' limits.
// A channel at duty 0 is disconnected from its timer and driven LOW by the port, so
// "off" is exactly LOW rather than a PWM glitch.
#pragma once

#include <stdint.h>

namespace board {

void h_bridge_begin();  // safe state: enable LOW, both inputs LOW
// duty > 0 drives right (D11), duty < 0 drives left (D10), |duty| is clamped to 255 (the
// controller has already applied the motor polarity). enable = false is the safe state
// whatever duty says.
void h_bridge_apply(int16_t duty, bool enable);
void h_bridge_safe_state();

}  // namespace board

// Encoder channels A (D2, INT0) and B (D3, INT1): an interrupt on any logical change of
// either channel, so the controller sees every edge (4x decoding).
#pragma once

#include <stdint.h>

namespace board {

void encoder_input_begin();

// Both channel levels, read in one instruction so they are consistent: bit 0 = A, bit 1 = B.
inline uint8_t encoder_levels(uint8_t pind) {
  return static_cast<uint8_t>((pind >> 2) & 0x03);  // PD2 = A, PD3 = B
}

}  // namespace board

// Why the chip last reset (MCUSR bits PORF, EXTRF, BORF, WDRF), saved before it is cleared.
#pragma once

#include <stdint.h>

extern uint8_t board_reset_cause;

// Timer0: the 1 kHz control tick and the free-running microsecond clock.
// CTC mode, prescaler 64, OCR0A 249: one compare match every 250 x 4 us = 1 ms.
#pragma once

#include <stdint.h>

namespace board {

void tick_timer_begin();
// Call first thing in the TIMER0_COMPA ISR (interrupts off there).
void tick_timer_count_from_isr();
// Microseconds since start, 4 us resolution, wraps after 71.6 minutes. Cheap: no
// multiplication or division.
uint32_t tick_timer_us();
// Milliseconds since start, from tick_timer_us() (a 32-bit division: not for hot paths;
// wraps with it).
uint32_t tick_timer_ms();
// Ticks since start, modulo 256: changes at every tick (the watchdog is fed only while it does).
uint8_t tick_timer_ticks();

}  // namespace board

#include "board/tick_timer.hpp"

#include <avr/io.h>
#include <util/atomic.h>

namespace board {
namespace {
const uint8_t counts_per_ms = 250;  // 16 MHz / 64 = 250 kHz -> 4 us per count
// Microseconds at the last tick, kept by the tick itself: reading the clock is then an
// addition, not a 32-bit multiplication (it is read in every bus interrupt, on the bus's
// critical path).
volatile uint32_t us_at_tick = 0;
volatile uint8_t ticks = 0;
}  // namespace

void tick_timer_begin() {
  TCCR0A = _BV(WGM01);  // CTC, TOP = OCR0A
  TCCR0B = _BV(CS01) | _BV(CS00);  // clk/64
  OCR0A = counts_per_ms - 1;
  TCNT0 = 0;
  TIFR0 = _BV(OCF0A);
  TIMSK0 = _BV(OCIE0A);
}

void tick_timer_count_from_isr() {
  us_at_tick = us_at_tick + 1000u;
  ticks = static_cast<uint8_t>(ticks + 1);
}

uint8_t tick_timer_ticks() { return ticks; }

uint32_t tick_timer_ms() { return tick_timer_us() / 1000u; }

uint32_t tick_timer_us() {
  uint32_t us;
  uint8_t counts;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    us = us_at_tick;
    counts = TCNT0;
    // A compare match not yet serviced (we are masked): TCNT0 already restarted from 0.
    if ((TIFR0 & _BV(OCF0A)) && counts < counts_per_ms - 1) us += 1000u;
  }
  return us + static_cast<uint16_t>(counts * 4u);
}

}  // namespace board

#include "board/tick_timer.hpp"

#include <avr/io.h>
#include <util/atomic.h>

namespace board {
namespace {
const uint8_t counts_per_ms = 250;  // 16 MHz / 64 = 250 kHz -> 4 us per count
volatile uint32_t ms_count = 0;
}  // namespace

void tick_timer_begin() {
  TCCR0A = _BV(WGM01);  // CTC, TOP = OCR0A
  TCCR0B = _BV(CS01) | _BV(CS00);  // clk/64
  OCR0A = counts_per_ms - 1;
  TCNT0 = 0;
  TIFR0 = _BV(OCF0A);
  TIMSK0 = _BV(OCIE0A);
}

void tick_timer_count_from_isr() { ms_count = ms_count + 1; }

uint32_t tick_timer_ms() {
  uint32_t ms;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { ms = ms_count; }
  return ms;
}

uint32_t tick_timer_us() {
  uint32_t ms;
  uint8_t counts;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    ms = ms_count;
    counts = TCNT0;
    // A compare match not yet serviced (we are masked): TCNT0 already restarted from 0.
    if ((TIFR0 & _BV(OCF0A)) && counts < counts_per_ms - 1) ms += 1;
  }
  return ms * 1000UL + static_cast<uint32_t>(counts) * 4UL;
}

}  // namespace board

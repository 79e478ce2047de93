#include "board/select_line.hpp"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "board/bus_events.hpp"
#include "board/pins.hpp"
#include "board/uart.hpp"

namespace board {
namespace {
// The level last reported, so that a glitch shorter than the ISR latency (two edges, one
// interrupt) is not reported as an edge that did not change anything.
volatile bool reported_high = false;
}  // namespace

void select_line_begin() {
  DDRB &= static_cast<uint8_t>(~_BV(select_bit));
  PORTB &= static_cast<uint8_t>(~_BV(select_bit));  // no pull-up: the master drives it
  reported_high = (PINB & _BV(select_bit)) != 0;
  if (reported_high) bus_event_push_from_isr(select_high_event);
  PCMSK0 = _BV(PCINT4);
  PCIFR = _BV(PCIF0);
  PCICR |= _BV(PCIE0);
}

bool select_line_high() { return (PINB & _BV(select_bit)) != 0; }

}  // namespace board

ISR(PCINT0_vect) {
  const bool high = (PINB & _BV(board::select_bit)) != 0;
  if (high == board::reported_high) return;
  board::reported_high = high;
  // The master lowers select right after the stop bit of its last byte. If the RX ISR has
  // not run yet (another ISR was busy), this ISR, which has the higher priority, would
  // queue the select edge before that byte and the joint would abandon the transaction.
  board::uart_take_received_from_isr();
  // READY's or STATUS's first byte before anything else (board/uart.hpp, uart_send_ahead):
  // the controller is handed this edge in this interrupt, or, while the control tick
  // computes, by the main loop right after it (the byte is known already: the tick does not
  // touch the bus transaction, and nothing is queued before this edge).
  uint8_t ahead;
  if (!board::bus_events_pending() && board::bus_byte_ahead(high, &ahead)) board::uart_send_ahead(ahead);
  board::bus_event_push_from_isr(high ? board::select_high_event : board::select_low_event);
  board::bus_events_queued_from_isr();
}

// Bus events in the order the hardware saw them: received bytes (UART RX ISR) and select
// edges (pin-change ISR) share one queue, so the main loop never hands the controller a
// byte that arrived after select fell before that fall (or the other way round).
#pragma once

#include <stdint.h>

namespace board {

// 0x000..0x0FF: a received byte; select_low_event / select_high_event: a select edge.
typedef uint16_t BusEvent;
const BusEvent select_low_event = 0x100;
const BusEvent select_high_event = 0x101;

// Called from ISRs only (interrupts are off there).
void bus_event_push_from_isr(BusEvent event);
// Defined by the firmware: the ISRs call it after queuing events (interrupts off), so that
// it may handle them at once.
void bus_events_queued_from_isr();
// Defined by the firmware (joint_isrs.cpp): the first byte of the word the controller will
// answer a select edge with, if it answers one (board/uart.hpp, uart_send_ahead).
bool bus_byte_ahead(bool select_high, uint8_t* byte);
// Defined by the firmware: whether bus_events_queued_from_isr() hands events on at once.
bool bus_events_handled_in_isr();
// Main loop: the next event, if any.
bool bus_event_pop(BusEvent* event);
bool bus_events_pending();
// Events lost because the queue was full (the main loop stalled): a diagnostic counter.
uint8_t bus_events_lost();

}  // namespace board

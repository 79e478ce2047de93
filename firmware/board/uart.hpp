// USART0, interrupt driven, with ring buffers. Received bytes go to the bus event queue
// (board/bus_events.hpp); bytes to send go through a small TX ring drained by the UDRE ISR.
//
// The bus TX lines of all joints are diode-OR'ed, so the transmitter is OFF (TXEN0 clear,
// PD1 an input without pull-up = high-Z) except while the controller allows this joint to
// drive TX. Always U2X0 (double speed): 9600 baud -> UBRR 207 (+0.2 %), 115200 -> UBRR 16
// (117647 baud, +2.1 %, inside the +-4.5 % that 8N1 tolerates; docs/firmware.md).
#pragma once

#include <stdint.h>

namespace board {

void uart_begin(uint32_t baud);  // receiver on, transmitter off (high-Z)
void uart_end();                 // receiver and transmitter off

void uart_enable_transmitter();
bool uart_transmitter_enabled();
// Turns the transmitter off once every queued byte is in the UART (which drives the pin
// until the last of them has fully left); true when it is off.
bool uart_release_transmitter_when_idle();

bool uart_tx_has_room();
bool uart_queue_tx(uint8_t byte);  // false if the TX ring is full (nothing queued)
void uart_discard_tx();            // drops queued bytes not yet handed to the hardware

// The first byte of the word the controller will answer an event with, written to the UART
// at once if it is idle, before the controller computes that word: from the select
// interrupt READY's as select rises and STATUS's as it falls (bus_byte_ahead, with nothing
// queued before the edge), from handle_next_bus_event a get_position's RESPONSE. The
// controller, handed the event next, queues that word, and its first byte is then left out.
void uart_send_ahead(uint8_t byte);
// After the controller has queued its answer to the edge or byte: a byte sent ahead that it
// did not queue is not looked for any more.
void uart_forget_ahead();

// From another ISR: moves a byte the UART has received but the RX ISR has not yet taken
// into the bus event queue, so that it is queued before whatever that ISR queues next.
void uart_take_received_from_isr();

// Receive errors seen (framing or data overrun): a diagnostic counter.
uint8_t uart_rx_errors();

}  // namespace board

#include "board/uart.hpp"

#include <avr/interrupt.h>
#include <avr/io.h>
#include <util/atomic.h>

#include "board/bus_events.hpp"
#include "board/pins.hpp"
#include "board/ring_buffer.hpp"

namespace board {
namespace {
// A reply is at most 2 words in flight (RESPONSE, then STATUS later): 8 bytes is plenty.
RingBuffer<uint8_t, 8> tx_ring;
// The transmitter is to be turned off as soon as the ring has been handed to the UART.
volatile bool release_wanted = false;
volatile uint8_t rx_errors = 0;
// A word's first byte went out from the select interrupt (uart_send_ahead): the
// controller's copy of it, the next byte queued, is not sent again.
bool byte_sent_ahead = false;

// Turning TXEN0 off takes effect only once the data register and the shift register hold
// nothing more to send (datasheet, "Disabling the Transmitter"): the UART itself lets go
// of the pin right after the last stop bit. So the transmitter is turned off as soon as
// the last byte is in the UART, not from an interrupt after it has left, whose latency (an
// interrupt-masked section of up to ~80 us) let this joint hold TX while the next one,
// answering from its select interrupt, had already enabled its own.
void release_transmitter() {
  UCSR0B &= static_cast<uint8_t>(~(_BV(TXEN0) | _BV(UDRIE0)));
  release_wanted = false;
}
}  // namespace

void uart_begin(uint32_t baud) {
  UCSR0B = 0;
  // TX pin as input without pull-up: high-Z whenever the transmitter is off.
  DDRD &= static_cast<uint8_t>(~_BV(uart_tx_bit));
  PORTD &= static_cast<uint8_t>(~_BV(uart_tx_bit));
  // U2X0 before UBRR0: the chip does not care, but simavr computes the bit time only when
  // UBRR0L is written and would otherwise run the emulated UART at half speed.
  UCSR0A = _BV(U2X0);
  const uint32_t ubrr = (F_CPU + 4UL * baud) / (8UL * baud) - 1UL;
  UBRR0H = static_cast<uint8_t>(ubrr >> 8);
  UBRR0L = static_cast<uint8_t>(ubrr);
  UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);  // 8N1
  UCSR0B = _BV(RXEN0) | _BV(RXCIE0);
}

void uart_end() {
  UCSR0B = 0;
  tx_ring.clear();
}

void uart_enable_transmitter() {
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    release_wanted = false;  // allowed again: no release pending
    UCSR0B |= _BV(TXEN0);
  }
}

bool uart_transmitter_enabled() { return (UCSR0B & _BV(TXEN0)) != 0; }

bool uart_release_transmitter_when_idle() {
  if (!(UCSR0B & _BV(TXEN0))) return true;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    if (tx_ring.empty()) {
      release_transmitter();
    } else {
      release_wanted = true;  // the UDRE ISR does it once it has handed on the last byte
    }
  }
  return !(UCSR0B & _BV(TXEN0));
}

bool uart_tx_has_room() { return !tx_ring.full(); }

void uart_forget_ahead() { byte_sent_ahead = false; }

__attribute__((noinline)) void uart_send_ahead(uint8_t byte) {
  if (!tx_ring.empty()) return;
  uart_enable_transmitter();  // as the controller's word would, a few microseconds later
  if (!(UCSR0A & _BV(UDRE0))) return;  // still sending: the word goes the usual way
  UDR0 = byte;
  byte_sent_ahead = true;
}

bool uart_queue_tx(uint8_t byte) {
  if (byte_sent_ahead) {
    byte_sent_ahead = false;
    return true;
  }
  // Nothing queued and the data register empty: straight to the hardware, without waiting
  // for the UDRE interrupt (part of every bus turnaround). Callers mask interrupts.
  if (tx_ring.empty() && (UCSR0A & _BV(UDRE0))) {
    UDR0 = byte;
    return true;
  }
  if (!tx_ring.push(byte)) return false;
  // The UDRE ISR moves it to the hardware (and clears UDRIE0 itself: mask while we set it).
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { UCSR0B |= _BV(UDRIE0); }
  return true;
}

void uart_discard_tx() { tx_ring.clear(); }

uint8_t uart_rx_errors() { return rx_errors; }

}  // namespace board

namespace board {
namespace {
void take_received_byte() {
  const uint8_t status = UCSR0A;
  const uint8_t byte = UDR0;
  if (status & (_BV(FE0) | _BV(DOR0))) {
    if (rx_errors != 0xFF) rx_errors = static_cast<uint8_t>(rx_errors + 1);
  }
  // A byte with a framing error is still handed on: the controller rejects what it cannot
  // parse, and dropping it would shift every later word by one byte.
  bus_event_push_from_isr(byte);
}
}  // namespace

void uart_take_received_from_isr() {
  while (UCSR0A & _BV(RXC0)) take_received_byte();
}
}  // namespace board

ISR(USART_RX_vect) {
  board::take_received_byte();
  board::bus_events_queued_from_isr();
}

ISR(USART_UDRE_vect) {
  uint8_t byte;
  if (board::tx_ring.pop(&byte)) UDR0 = byte;
  if (board::tx_ring.empty()) {
    if (board::release_wanted) {
      board::release_transmitter();
    } else {
      UCSR0B &= static_cast<uint8_t>(~_BV(UDRIE0));
    }
  }
}

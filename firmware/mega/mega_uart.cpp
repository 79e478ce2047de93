#include "mega/mega_uart.hpp"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "board/ring_buffer.hpp"

namespace mega {
namespace {

struct Channel {
  board::RingBuffer<uint8_t, 128> tx;
  volatile uint8_t errors;
};

Channel channels[2];
board::RingBuffer<uint8_t, 128> upstream_rx;  // the bus has none: bus_byte_received()

uint16_t ubrr_for(uint32_t baud) { return static_cast<uint16_t>((F_CPU / 8 + baud / 2) / baud - 1); }

void count_error(Channel& c) {
  if (c.errors != 0xFF) c.errors = static_cast<uint8_t>(c.errors + 1);
}

}  // namespace

void uart_begin(Port port, uint32_t baud) {
  const uint16_t ubrr = ubrr_for(baud);
  // U2X and the frame format before UBRR: the chip does not care, but simavr computes the
  // bit time only when UBRRnL is written, and with U2X still clear it would run the
  // emulated UART at half speed (replies and bus commands at half the baud rate).
  if (port == Port::upstream) {
    UCSR0A = _BV(U2X0);
    UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);  // 8N1
    UBRR0H = static_cast<uint8_t>(ubrr >> 8);
    UBRR0L = static_cast<uint8_t>(ubrr);  // last: simavr takes the bit time here
    UCSR0B = _BV(RXEN0) | _BV(TXEN0) | _BV(RXCIE0);
  } else {
    UCSR1A = _BV(U2X1);
    UCSR1C = _BV(UCSZ11) | _BV(UCSZ10);
    UBRR1H = static_cast<uint8_t>(ubrr >> 8);
    UBRR1L = static_cast<uint8_t>(ubrr);
    UCSR1B = _BV(RXEN1) | _BV(TXEN1) | _BV(RXCIE1);
  }
}

bool uart_receive_upstream(uint8_t* byte) { return upstream_rx.pop(byte); }

namespace {

// Bytes are queued: clear TXC (by writing 1: it is set again only when the last byte has
// left) and let the data-register-empty interrupt send them.
void start_sending(Port port) {
  if (port == Port::upstream) {
    UCSR0A = static_cast<uint8_t>(UCSR0A | _BV(TXC0));
    UCSR0B = static_cast<uint8_t>(UCSR0B | _BV(UDRIE0));
  } else {
    UCSR1A = static_cast<uint8_t>(UCSR1A | _BV(TXC1));
    UCSR1B = static_cast<uint8_t>(UCSR1B | _BV(UDRIE1));
  }
}

// The UART is idle and nothing waits: the byte goes out now, not from the UDRE interrupt
// (a bus turnaround shorter by that interrupt's entry). Interrupts masked: the UDRE
// interrupt may not take a byte in between.
bool send_now(Port port, uint8_t byte) {
  bool sent = false;
  const uint8_t sreg = SREG;
  cli();
  if (channels[uint8_t(port)].tx.empty()) {
    if (port == Port::upstream && (UCSR0A & _BV(UDRE0)) != 0) {
      UCSR0A = static_cast<uint8_t>(UCSR0A | _BV(TXC0));
      UDR0 = byte;
      sent = true;
    } else if (port == Port::bus && (UCSR1A & _BV(UDRE1)) != 0) {
      UCSR1A = static_cast<uint8_t>(UCSR1A | _BV(TXC1));
      UDR1 = byte;
      sent = true;
    }
  }
  SREG = sreg;
  return sent;
}

}  // namespace

bool uart_send(Port port, uint8_t byte) {
  if (send_now(port, byte)) return true;
  Channel& c = channels[uint8_t(port)];
  if (!c.tx.push(byte)) return false;
  start_sending(port);
  return true;
}

uint8_t uart_send_bytes(Port port, const uint8_t* bytes, uint8_t count) {
  Channel& c = channels[uint8_t(port)];
  uint8_t queued = 0;
  while (queued < count && c.tx.push(bytes[queued])) ++queued;
  if (queued == 0) return 0;
  // Once for the whole run (a 30-byte reply byte by byte took the Mega's loop 3,000 cycles).
  start_sending(port);
  return queued;
}

bool uart_tx_idle(Port port) {
  Channel& c = channels[uint8_t(port)];
  if (!c.tx.empty()) return false;
  return port == Port::upstream ? (UCSR0A & _BV(TXC0)) != 0 : (UCSR1A & _BV(TXC1)) != 0;
}

uint8_t uart_rx_errors(Port port) { return channels[uint8_t(port)].errors; }

void bus_notify_tx_done() {
  const uint8_t sreg = SREG;
  cli();
  if (uart_tx_idle(Port::bus)) {
    SREG = sreg;
    bus_tx_done();
    return;
  }
  UCSR1B = static_cast<uint8_t>(UCSR1B | _BV(TXCIE1));
  SREG = sreg;
}

}  // namespace mega

using mega::channels;
using mega::upstream_rx;

ISR(USART0_RX_vect) {
  const uint8_t status = UCSR0A;
  const uint8_t byte = UDR0;
  if ((status & (_BV(FE0) | _BV(DOR0))) != 0 || !mega::upstream_rx.push(byte)) mega::count_error(channels[0]);
}

ISR(USART0_UDRE_vect) {
  uint8_t byte;
  if (channels[0].tx.pop(&byte)) {
    UCSR0A = static_cast<uint8_t>(UCSR0A | _BV(TXC0));  // set again only once this byte has left
    UDR0 = byte;
  } else {
    UCSR0B = static_cast<uint8_t>(UCSR0B & ~_BV(UDRIE0));
  }
}

ISR(USART1_RX_vect) {
  const uint8_t status = UCSR1A;
  const uint8_t byte = UDR1;
  if ((status & (_BV(FE1) | _BV(DOR1))) != 0) {
    mega::count_error(channels[1]);
    return;
  }
  mega::bus_byte_received(byte);
}

// The shift register ran empty (TXC1, cleared by running this): done if nothing waits.
ISR(USART1_TX_vect) {
  if (!channels[1].tx.empty()) return;
  UCSR1B = static_cast<uint8_t>(UCSR1B & ~_BV(TXCIE1));
  mega::bus_tx_done();
}

ISR(USART1_UDRE_vect) {
  uint8_t byte;
  if (channels[1].tx.pop(&byte)) {
    UCSR1A = static_cast<uint8_t>(UCSR1A | _BV(TXC1));
    UDR1 = byte;
  } else {
    UCSR1B = static_cast<uint8_t>(UCSR1B & ~_BV(UDRIE1));
  }
}

// The Mega's two UARTs as the arm controller uses them: UART0 = Robot Commands upstream
// (the USB serial port), UART1 = the joint bus (TX1 pin 18, RX1 pin 19). Received bytes
// go to a ring buffer from the RX interrupt; bytes to send go through a ring drained by
// the UDRE interrupt. Always U2X (double speed): 9600 -> UBRR 207 (+0.2 %), 115200 ->
// UBRR 16 (+2.1 %, inside the 8N1 tolerance).
#pragma once

#include <stdint.h>

namespace mega {

enum class Port : uint8_t { upstream = 0, bus = 1 };

void uart_begin(Port port, uint32_t baud);
bool uart_receive(Port port, uint8_t* byte);  // false if nothing is waiting
bool uart_send(Port port, uint8_t byte);      // false if the TX ring is full
// Queues bytes up to a full ring; the number queued.
uint8_t uart_send_bytes(Port port, const uint8_t* bytes, uint8_t count);
// Every queued byte has fully left the shift register.
bool uart_tx_idle(Port port);
uint8_t uart_rx_errors(Port port);  // framing or overrun errors (saturating)

}  // namespace mega

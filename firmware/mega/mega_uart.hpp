// The Mega's two UARTs as the arm controller uses them: UART0 = Robot Commands upstream
// (the USB serial port), UART1 = the joint bus (TX1 pin 18, RX1 pin 19). Bytes received
// upstream go to a ring buffer from the RX interrupt; a byte received from the joint bus
// goes from its RX interrupt straight to bus_byte_received(), which the owner defines (the
// bus master answers from there: no main-loop pass in a bus turnaround). A byte to send
// goes straight to the UART when it is idle, else through a ring drained by the UDRE
// interrupt. Always U2X (double speed): 9600 -> UBRR 207 (+0.2 %), 115200 -> UBRR 16
// (+2.1 %, inside the 8N1 tolerance).
#pragma once

#include <stdint.h>

namespace mega {

enum class Port : uint8_t { upstream = 0, bus = 1 };

void uart_begin(Port port, uint32_t baud);
bool uart_receive_upstream(uint8_t* byte);  // false if nothing is waiting
// Defined by the owner; called from the joint bus's RX interrupt with each byte received
// without a framing or overrun error.
void bus_byte_received(uint8_t byte);
// Calls bus_tx_done(), defined by the owner, from the joint bus's TX-complete interrupt
// once every byte queued so far has left the wire (at once if they have); once.
void bus_notify_tx_done();
void bus_tx_done();
bool uart_send(Port port, uint8_t byte);      // false if the TX ring is full
// Queues bytes up to a full ring; the number queued.
uint8_t uart_send_bytes(Port port, const uint8_t* bytes, uint8_t count);
// Every queued byte has fully left the shift register.
bool uart_tx_idle(Port port);
uint8_t uart_rx_errors(Port port);  // framing or overrun errors (saturating)

}  // namespace mega

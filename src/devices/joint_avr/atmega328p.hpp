// The few ATmega328P facts the harness needs (data-space addresses, bits, vector numbers),
// from the ATmega328P datasheet. Host code cannot include avr-libc's <avr/io.h>.
#pragma once

#include <cstdint>

namespace armctl::joint_avr::atmega328p {

inline constexpr std::uint32_t clock_hz = 16'000'000;  // Arduino Nano crystal

// Data-space addresses of I/O registers.
inline constexpr std::uint16_t pinb = 0x23, ddrb = 0x24, portb = 0x25;
inline constexpr std::uint16_t pind = 0x29, ddrd = 0x2A, portd = 0x2B;
inline constexpr std::uint16_t tccr1a = 0x80, tccr1b = 0x81, ocr1bl = 0x8A;
inline constexpr std::uint16_t tccr2a = 0xB0, tccr2b = 0xB1, ocr2a = 0xB3;
inline constexpr std::uint16_t ucsr0a = 0xC0, ucsr0b = 0xC1, ucsr0c = 0xC2;
// The ATmega2560 has UART0 at the same addresses and UART1 8 bytes above (UCSR1A 0xC8).
inline constexpr std::uint16_t uart1_offset = 8;

// Bits.
inline constexpr std::uint8_t com1b1 = 5, com1b0 = 4;  // TCCR1A
inline constexpr std::uint8_t com2a1 = 7, com2a0 = 6;  // TCCR2A
inline constexpr std::uint8_t rxen0 = 4, txen0 = 3;    // UCSR0B

// Interrupt vector numbers (datasheet table 12-6; reset is 0).
inline constexpr int vector_int0 = 1;
inline constexpr int vector_int1 = 2;
inline constexpr int vector_pcint0 = 3;
inline constexpr int vector_timer0_compa = 14;
inline constexpr int vector_usart_rx = 18;
inline constexpr int vector_usart_udre = 19;
inline constexpr int vector_count = 26;

// The hardware's interrupt response (push PC, jump to the vector) takes 4 cycles that
// simavr 1.6 does not count; the harness adds them to every ISR it measures.
inline constexpr std::uint64_t interrupt_response_cycles = 4;

}  // namespace armctl::joint_avr::atmega328p

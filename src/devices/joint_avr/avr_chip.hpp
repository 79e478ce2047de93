// One emulated ATmega328P (libsimavr, GPL: a test tool only, never linked into armctl's
// product code) running a firmware ELF at 16 MHz, with the pins, UART and cycle counts the
// HIL harness needs. Time is in CPU cycles; the chip runs only inside run_to_cycle().
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>

struct avr_t;
struct avr_irq_t;
struct avr_uart_t;

namespace armctl::joint_avr {

// Cycle statistics of one interrupt vector: from dispatch to the end of RETI, plus the
// hardware's 4-cycle interrupt response (atmega328p.hpp). An ISR that re-enables
// interrupts can be interrupted: max_cycles counts that time too, max_own_cycles does not.
struct IsrStats {
  std::uint64_t count = 0;
  std::uint64_t max_cycles = 0;
  std::uint64_t max_own_cycles = 0;
  std::uint64_t total_cycles = 0;
};

// Drive seen on the H-bridge inputs: left/right high-time fractions (PWM duty from the
// timer registers, or the plain port level when the timer is disconnected) and enable.
struct BridgeInputs {
  double left = 0.0;
  double right = 0.0;
  bool enable = false;
};

class AvrChip {
 public:
  // Loads the ELF; throws ArmctlError(io) if it cannot be read.
  explicit AvrChip(const std::string& elf_path);
  ~AvrChip();
  AvrChip(const AvrChip&) = delete;
  AvrChip& operator=(const AvrChip&) = delete;

  // EEPROM contents (as avrdude -U eeprom:w would leave them); takes effect at the next
  // read by the firmware, so set it before the first run or follow it with reset().
  void write_eeprom(std::uint16_t address, std::span<const std::uint8_t> bytes);
  // A reset pulse (RESET pin): the firmware starts over; EEPROM is kept.
  void reset();
  // RESET held low: the chip does not run and every pin is a high-Z input.
  void set_held_in_reset(bool held);
  bool held_in_reset() const { return held_in_reset_; }

  // Runs the firmware until the cycle counter reaches `cycle` (it may pass it by the few
  // cycles of the last instruction). False if the core stopped (crash, sleep with
  // interrupts off).
  bool run_to_cycle(std::uint64_t cycle);
  std::uint64_t cycle() const;
  bool stopped() const;

  // An input pin driven from outside ('B' or 'D', bit 0..7). Only changes reach the chip.
  void drive_pin(char port, int bit, bool level);

  // A byte whose stop bit ends now: the UART flags it received at once (RXC).
  void uart_receive(std::uint8_t byte);
  // Called for each byte the firmware writes to UDR0 with the transmitter on, with the
  // cycle of the write.
  void set_uart_output(std::function<void(std::uint8_t, std::uint64_t)> sink) {
    uart_output_ = std::move(sink);
  }
  bool uart_transmitter_enabled() const;
  bool uart_receiver_enabled() const;

  BridgeInputs bridge_inputs() const;
  bool led() const;
  std::uint8_t read_data(std::uint16_t address) const;

  const IsrStats& isr_stats(int vector) const { return isr_stats_.at(static_cast<std::size_t>(vector)); }
  void clear_isr_stats();

 private:
  static void on_uart_output_irq(avr_irq_t* irq, std::uint32_t value, void* param);
  static void on_isr_running_irq(avr_irq_t* irq, std::uint32_t value, void* param);
  void connect();
  void reapply_pins();
  void apply_reset_values();
  void correct_uart_frame_time();
  bool output_pin(std::uint16_t ddr, std::uint16_t port, int bit) const;

  avr_t* avr_ = nullptr;
  avr_uart_t* uart_ = nullptr;
  bool held_in_reset_ = false;
  std::uint64_t corrected_cycles_per_byte_ = 0;
  std::function<void(std::uint8_t, std::uint64_t)> uart_output_;
  // Levels driven from outside: [0] port B, [1] port D; mask says which bits we drive.
  std::array<std::uint8_t, 2> driven_mask_{};
  std::array<std::uint8_t, 2> driven_level_{};
  struct VectorProbe {
    AvrChip* chip;
    int vector;
    std::uint64_t entered_at;
    std::uint64_t nested_cycles;  // spent in ISRs that interrupted this one
  };
  std::array<int, 32> running_{};  // stack of vectors being serviced (nesting)
  int running_depth_ = 0;
  std::array<VectorProbe, 32> probes_{};
  std::array<IsrStats, 32> isr_stats_{};
};

}  // namespace armctl::joint_avr

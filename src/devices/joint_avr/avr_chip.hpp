// One emulated AVR (libsimavr, GPL: a test tool only, never linked into armctl's product
// code) running a firmware ELF at 16 MHz, with the pins, UARTs and cycle counts the HIL
// harness needs: the joint controllers' ATmega328P, and the Mega controller's ATmega2560
// (ChipModel). Time is in CPU cycles; the chip runs only inside run_to_cycle().
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

// The chip a firmware runs on.
struct ChipModel {
  const char* mcu;
  std::uint16_t eeprom_bytes;
  int vector_count;  // interrupt vectors, reset included
  int uart_count;
};
inline constexpr ChipModel atmega328p_model{"atmega328p", 1024, 26, 1};
inline constexpr ChipModel atmega2560_model{"atmega2560", 4096, 57, 2};

class AvrChip {
 public:
  // Loads the ELF; throws ArmctlError(io) if it cannot be read.
  explicit AvrChip(const std::string& elf_path, const ChipModel& model = atmega328p_model);
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

  // The voltage on analog input `channel` (ADC0..15) from now on, in mV (AVcc = 5000 mV).
  void set_adc_millivolts(int channel, std::uint32_t millivolts);

  // A byte whose stop bit ends now: UART `uart` flags it received at once (RXC).
  void uart_receive(std::uint8_t byte, int uart = 0);
  // Called for each byte the firmware writes to UDRn with the transmitter on, with the
  // cycle of the write.
  void set_uart_output(std::function<void(std::uint8_t, std::uint64_t)> sink, int uart = 0) {
    uart_output_.at(static_cast<std::size_t>(uart)) = std::move(sink);
  }
  // Called with (bit, level, cycle) whenever the firmware changes an output pin of `port`
  // ('A'..'L'): the select lines of the Mega controller.
  void watch_output_port(char port, std::function<void(int, bool, std::uint64_t)> sink);
  // Called with (value, cycle) whenever the firmware writes the I/O register at data-space
  // `address` (e.g. GPIOR0 = 0x3E, a register with no pin: a heartbeat the harness times).
  void watch_register_write(std::uint16_t address, std::function<void(std::uint8_t, std::uint64_t)> sink);
  bool uart_transmitter_enabled() const;
  bool uart_receiver_enabled() const;

  BridgeInputs bridge_inputs() const;
  bool led() const;
  std::uint8_t read_data(std::uint16_t address) const;

  const IsrStats& isr_stats(int vector) const { return isr_stats_.at(static_cast<std::size_t>(vector)); }
  void clear_isr_stats();

 private:
  static void on_uart_output_irq(avr_irq_t* irq, std::uint32_t value, void* param);
  static void on_uart1_output_irq(avr_irq_t* irq, std::uint32_t value, void* param);
  static void on_port_pin_irq(avr_irq_t* irq, std::uint32_t value, void* param);
  static void on_isr_running_irq(avr_irq_t* irq, std::uint32_t value, void* param);
  static void on_register_write(avr_t* avr, std::uint16_t address, std::uint8_t value, void* param);
  static void on_uart_control_write(avr_t* avr, std::uint16_t address, std::uint8_t value, void* param);
  void connect();
  void reapply_pins();
  void apply_reset_values();
  void correct_uart_frame_time();
  void model_uart_data_register();
  bool output_pin(std::uint16_t ddr, std::uint16_t port, int bit) const;

  ChipModel model_;
  avr_t* avr_ = nullptr;
  std::array<avr_uart_t*, 2> uarts_{};
  avr_uart_t* uart_ = nullptr;  // uarts_[0]
  bool held_in_reset_ = false;
  std::array<std::uint64_t, 2> corrected_cycles_per_byte_{};
  std::array<std::function<void(std::uint8_t, std::uint64_t)>, 2> uart_output_;
  struct PinProbe {
    AvrChip* chip;
    int bit;
  };
  std::array<PinProbe, 8> pin_probes_{};
  std::function<void(int, bool, std::uint64_t)> port_output_;
  std::function<void(std::uint8_t, std::uint64_t)> register_write_;
  // Levels driven from outside: [0] port B, [1] port D; mask says which bits we drive.
  std::array<std::uint8_t, 2> driven_mask_{};
  std::array<std::uint8_t, 2> driven_level_{};
  struct VectorProbe {
    AvrChip* chip;
    int vector;
    std::uint64_t entered_at;
    std::uint64_t nested_cycles;  // spent in ISRs that interrupted this one
  };
  std::array<int, 64> running_{};  // stack of vectors being serviced (nesting)
  int running_depth_ = 0;
  std::array<VectorProbe, 64> probes_{};
  std::array<IsrStats, 64> isr_stats_{};
};

}  // namespace armctl::joint_avr

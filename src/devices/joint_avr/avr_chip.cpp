#include "devices/joint_avr/avr_chip.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <vector>

#include "core/error.hpp"
#include "devices/joint_avr/atmega328p.hpp"

extern "C" {
#include <avr_adc.h>
#include <avr_eeprom.h>
#include <avr_extint.h>
#include <avr_ioport.h>
#include <avr_uart.h>
#include <sim_avr.h>
#include <sim_elf.h>
#include <sim_io.h>
}

namespace armctl::joint_avr {
namespace {

namespace m = atmega328p;

// simavr's default sleep callback usleep()s to keep pace with the wall clock; the harness
// runs on simulated time only, so sleeping just lets cycles pass.
void no_wall_clock_sleep(avr_t*, avr_cycle_count_t) {}

// Lets run_to_cycle() stop a sleeping core at its target: a sleeping core skips straight to
// the next cycle timer, and this is one. It re-arms itself one cycle later, because simavr
// processes the due timers first and then sleeps until the *next* one: a one-shot timer
// would let the core sleep on to the following timer event (up to 1 ms past the target).
avr_cycle_count_t stop_here(avr_t*, avr_cycle_count_t when, void*) { return when + 1; }

// simavr logs through one process-wide function; keep errors, drop its chatter ("Loaded
// 7274 .text ...", traces).
void quiet_logger(avr_t*, const int level, const char* format, va_list args) {
  if (level > LOG_ERROR) return;
  std::vfprintf(stderr, format, args);
}

void free_firmware(elf_firmware_t& f) {
  std::free(f.flash);
  std::free(f.eeprom);
  std::free(f.fuse);
  std::free(f.lockbits);
#if ELF_SYMBOLS
  for (std::uint32_t i = 0; i < f.symbolcount; ++i) std::free(f.symbol[i]);
  std::free(f.symbol);
#endif
}

int port_index(char port) {
  if (port == 'B') return 0;
  if (port == 'D') return 1;
  throw ArmctlError(ErrorKind::invalid_argument,
                    std::string("AvrChip: input port '") + port + "' is not wired (use B or D)");
}

}  // namespace

AvrChip::AvrChip(const std::string& elf_path, const ChipModel& model) : model_(model) {
  static std::once_flag logger_installed;
  std::call_once(logger_installed, [] { avr_global_logger_set(quiet_logger); });
  elf_firmware_t firmware;
  std::memset(&firmware, 0, sizeof firmware);
  if (elf_read_firmware(elf_path.c_str(), &firmware) != 0 || firmware.flashsize == 0) {
    free_firmware(firmware);
    throw ArmctlError(ErrorKind::io, "cannot read the firmware ELF '" + elf_path +
                                         "' (build it: cmake --build <dir> --target armctl_firmware)");
  }
  avr_ = avr_make_mcu_by_name(model_.mcu);
  if (avr_ == nullptr) {
    free_firmware(firmware);
    throw ArmctlError(ErrorKind::unsupported, std::string("this libsimavr has no ") + model_.mcu + " core");
  }
  avr_init(avr_);
  avr_->log = LOG_ERROR;
  avr_load_firmware(avr_, &firmware);
  free_firmware(firmware);
  avr_->frequency = m::clock_hz;
  // 5 V supply and ADC reference (AVcc) as on the boards: the ADC model needs them.
  avr_->vcc = avr_->avcc = avr_->aref = 5000;
  avr_->sleep = no_wall_clock_sleep;
  // INT0/INT1 start in "low level" mode (EICRA = 0 at reset); simavr then polls the pin on
  // every cycle while it is low, and keeps polling after the firmware switches to "any
  // change". The firmware never uses level mode, so level polling is turned off.
  avr_extint_set_strict_lvl_trig(avr_, 0, 0);
  avr_extint_set_strict_lvl_trig(avr_, 1, 0);
  connect();
  apply_reset_values();
}

void AvrChip::set_adc_millivolts(int channel, std::uint32_t millivolts) {
  if (channel < 0 || channel > 15)
    throw ArmctlError(ErrorKind::invalid_argument, "AvrChip: ADC channel must be 0..15");
  avr_irq_t* irq = avr_io_getirq(avr_, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC0 + channel);
  if (irq == nullptr) throw ArmctlError(ErrorKind::unsupported, std::string("simavr ") + model_.mcu + " without ADC");
  avr_raise_irq(irq, millivolts);
}

AvrChip::~AvrChip() {
  if (avr_ != nullptr) {
    avr_terminate(avr_);
    std::free(avr_);
  }
}

void AvrChip::connect() {
  // No console dump of UART bytes, and no usleep() when the firmware polls the UART.
  for (int u = 0; u < model_.uart_count; ++u) {
    std::uint32_t flags = 0;
    avr_ioctl(avr_, AVR_IOCTL_UART_SET_FLAGS(static_cast<char>('0' + u)), &flags);
  }
  for (avr_io_t* io = avr_->io_port; io != nullptr; io = io->next) {
    if (std::strcmp(io->kind, "uart") != 0) continue;
    auto* uart = reinterpret_cast<avr_uart_t*>(io);
    const int index = uart->name - '0';
    if (index >= 0 && index < model_.uart_count) uarts_[static_cast<std::size_t>(index)] = uart;
  }
  for (int u = 0; u < model_.uart_count; ++u) {
    if (uarts_[static_cast<std::size_t>(u)] == nullptr)
      throw ArmctlError(ErrorKind::unsupported, std::string("simavr ") + model_.mcu + " without UART" + char('0' + u));
  }
  uart_ = uarts_[0];
  for (int u = 0; u < model_.uart_count; ++u) {
    avr_uart_t* uart = uarts_[static_cast<std::size_t>(u)];
    avr_register_io_write(avr_, uart->udrc.enable.reg, &AvrChip::on_uart_control_write, uart);
  }
  avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                          &AvrChip::on_uart_output_irq, this);
  if (model_.uart_count > 1) {
    avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ('1'), UART_IRQ_OUTPUT),
                            &AvrChip::on_uart1_output_irq, this);
  }
  for (int v = 1; v < model_.vector_count; ++v) {
    avr_irq_t* irq = avr_get_interrupt_irq(avr_, static_cast<std::uint8_t>(v));
    if (irq == nullptr) continue;
    probes_[static_cast<std::size_t>(v)] = VectorProbe{this, v, 0, 0};
    avr_irq_register_notify(irq + AVR_INT_IRQ_RUNNING, &AvrChip::on_isr_running_irq,
                            &probes_[static_cast<std::size_t>(v)]);
  }
}

void AvrChip::on_uart_control_write(avr_t* avr, std::uint16_t, std::uint8_t, void* param) {
  // Runs after simavr's own handler of UCSRnB. A real UART flags UDRE whenever its data
  // register is empty, so enabling UDRIE then interrupts at once. simavr 1.6 raises it on
  // enable only if its transmit timer is idle, and that timer runs on for one byte time
  // after the last byte has gone: a reply started just after a previous one waited up to a
  // byte time (a joint's STATUS after its RESPONSE: 1 ms at 9600).
  // The flag itself, too: simavr 1.6 clears UDRE with TXEN and leaves it clear after TXEN is
  // set until a byte has gone, where a real UART shows its empty data register whatever
  // TXEN is (firmware that writes UDR at once when UDRE is set, instead of waiting for the
  // interrupt, saw a full register).
  auto* uart = static_cast<avr_uart_t*>(param);
  if (uart->tx_cnt != 0) return;
  if (!avr_regbit_get(avr, uart->txen) || !avr_regbit_get(avr, uart->udrc.enable)) {
    avr_regbit_set(avr, uart->udrc.raised);  // UDRE, with or without the transmitter
  } else if (!uart->udrc.pending) {
    avr_raise_interrupt(avr, &uart->udrc);
  }
}

void AvrChip::on_uart_output_irq(avr_irq_t*, std::uint32_t value, void* param) {
  auto* self = static_cast<AvrChip*>(param);
  if (self->uart_output_[0]) self->uart_output_[0](static_cast<std::uint8_t>(value), self->avr_->cycle);
}

void AvrChip::on_uart1_output_irq(avr_irq_t*, std::uint32_t value, void* param) {
  auto* self = static_cast<AvrChip*>(param);
  if (self->uart_output_[1]) self->uart_output_[1](static_cast<std::uint8_t>(value), self->avr_->cycle);
}

void AvrChip::watch_output_port(char port, std::function<void(int, bool, std::uint64_t)> sink) {
  port_output_ = std::move(sink);
  for (int bit = 0; bit < 8; ++bit) {
    pin_probes_[static_cast<std::size_t>(bit)] = PinProbe{this, bit};
    avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ(port), bit), &AvrChip::on_port_pin_irq,
                            &pin_probes_[static_cast<std::size_t>(bit)]);
  }
}

void AvrChip::watch_register_write(std::uint16_t address,
                                   std::function<void(std::uint8_t, std::uint64_t)> sink) {
  register_write_ = std::move(sink);
  avr_register_io_write(avr_, address, &AvrChip::on_register_write, this);
}

void AvrChip::on_register_write(avr_t* avr, std::uint16_t address, std::uint8_t value, void* param) {
  auto* self = static_cast<AvrChip*>(param);
  avr_core_watch_write(avr, address, value);  // a write hook stores the value itself
  if (self->register_write_) self->register_write_(value, avr->cycle);
}

void AvrChip::on_port_pin_irq(avr_irq_t*, std::uint32_t value, void* param) {
  auto* probe = static_cast<PinProbe*>(param);
  AvrChip* self = probe->chip;
  if (self->port_output_) self->port_output_(probe->bit, value != 0, self->avr_->cycle);
}

void AvrChip::on_isr_running_irq(avr_irq_t*, std::uint32_t value, void* param) {
  auto* probe = static_cast<VectorProbe*>(param);
  AvrChip* self = probe->chip;
  if (value != 0) {
    probe->entered_at = self->avr_->cycle;
    probe->nested_cycles = 0;
    if (self->running_depth_ < static_cast<int>(self->running_.size())) {
      self->running_[static_cast<std::size_t>(self->running_depth_++)] = probe->vector;
    }
    return;
  }
  const std::uint64_t cycles = self->avr_->cycle - probe->entered_at + m::interrupt_response_cycles;
  if (self->running_depth_ > 0) --self->running_depth_;
  if (self->running_depth_ > 0) {
    const int outer = self->running_[static_cast<std::size_t>(self->running_depth_ - 1)];
    self->probes_[static_cast<std::size_t>(outer)].nested_cycles += cycles;
  }
  IsrStats& s = self->isr_stats_[static_cast<std::size_t>(probe->vector)];
  ++s.count;
  s.total_cycles += cycles;
  s.max_cycles = std::max(s.max_cycles, cycles);
  s.max_own_cycles = std::max(s.max_own_cycles, cycles - std::min(cycles, probe->nested_cycles));
}

void AvrChip::clear_isr_stats() { isr_stats_ = {}; }

void AvrChip::write_eeprom(std::uint16_t address, std::span<const std::uint8_t> bytes) {
  const std::size_t eeprom_bytes = model_.eeprom_bytes;
  if (bytes.empty()) return;
  if (address + bytes.size() > eeprom_bytes) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "AvrChip: EEPROM write outside 0.." + std::to_string(eeprom_bytes - 1));
  }
  std::vector<std::uint8_t> copy(bytes.begin(), bytes.end());
  avr_eeprom_desc_t desc;
  desc.ee = copy.data();
  desc.offset = address;
  desc.size = static_cast<std::uint32_t>(copy.size());
  // simavr 1.6 answers -1 ("not mine, keep asking") even when its EEPROM took the data;
  // the range was checked above.
  avr_ioctl(avr_, AVR_IOCTL_EEPROM_SET, &desc);
}

void AvrChip::apply_reset_values() {
  // simavr 1.6 sets TXEN0 at reset so that debug printf works without UART set-up; on the
  // real chip UCSRnB resets to 0 (TX pin high-Z until the firmware enables it).
  avr_->data[m::ucsr0b] = 0;
  if (model_.uart_count > 1) avr_->data[m::ucsr0b + m::uart1_offset] = 0;
}

void AvrChip::reset() {
  avr_reset(avr_);
  running_depth_ = 0;
  apply_reset_values();
  reapply_pins();
}

void AvrChip::set_held_in_reset(bool held) {
  if (held == held_in_reset_) return;
  held_in_reset_ = held;
  // Entering reset clears every I/O register (pins become inputs); leaving it starts the
  // firmware from the reset vector.
  avr_reset(avr_);
  running_depth_ = 0;
  apply_reset_values();
  reapply_pins();
}

void AvrChip::model_uart_data_register() {
  // A real UART moves a byte written to UDR into its shift register at once when that is
  // empty, and flags UDRE again: the data register is free while one byte shifts out, so
  // firmware can hand over the next byte and it follows back to back. simavr 1.6 keeps
  // UDRE clear until every byte written has gone, which left a gap of the UDRE interrupt's
  // latency after the first byte of every word on the bus. UDRE is flagged (and its
  // interrupt, when enabled, made pending) whenever fewer than two bytes are in the UART.
  for (int u = 0; u < model_.uart_count; ++u) {
    avr_uart_t* uart = uarts_[static_cast<std::size_t>(u)];
    if (uart->tx_cnt >= 2 || !avr_regbit_get(avr_, uart->txen)) continue;
    const bool raised = avr_regbit_get(avr_, uart->udrc.raised) != 0;
    if (raised && (uart->udrc.pending || !avr_regbit_get(avr_, uart->udrc.enable))) continue;
    avr_raise_interrupt(avr_, &uart->udrc);
  }
}

void AvrChip::correct_uart_frame_time() {
  // simavr 1.6 times a frame as start + data + parity + stop bits even when parity is off:
  // 11 bit times for 8N1 instead of 10. Real UDRE/TXC timing matters here (the firmware
  // releases TX on TXC), so bring it back to 10 bits whenever the firmware has set a baud.
  for (int u = 0; u < model_.uart_count; ++u) {
    avr_uart_t* uart = uarts_[static_cast<std::size_t>(u)];
    std::uint64_t& corrected = corrected_cycles_per_byte_[static_cast<std::size_t>(u)];
    const std::uint8_t ucsrc = avr_->data[m::ucsr0c + u * m::uart1_offset];
    const bool parity_on = (ucsrc & 0x30u) != 0;
    if (parity_on || uart->cycles_per_byte == corrected) continue;
    if (uart->cycles_per_byte % 11 != 0) continue;
    corrected = uart->cycles_per_byte / 11 * 10;
    uart->cycles_per_byte = corrected;
  }
}

std::uint64_t AvrChip::cycle() const { return avr_->cycle; }

bool AvrChip::stopped() const {
  return avr_->state == cpu_Done || avr_->state == cpu_Crashed || avr_->state == cpu_Stopped;
}

bool AvrChip::run_to_cycle(std::uint64_t target) {
  if (avr_->cycle >= target) return !stopped();
  if (held_in_reset_ || stopped()) {
    avr_->cycle = target;  // time passes, nothing runs
    return !stopped();
  }
  avr_cycle_timer_register(avr_, target - avr_->cycle, stop_here, this);
  while (avr_->cycle < target) {
    correct_uart_frame_time();
    model_uart_data_register();
    const int state = avr_run(avr_);
    if (state == cpu_Done || state == cpu_Crashed || state == cpu_Stopped) {
      avr_cycle_timer_cancel(avr_, stop_here, this);
      avr_->cycle = target;
      return false;
    }
  }
  avr_cycle_timer_cancel(avr_, stop_here, this);
  return true;
}

void AvrChip::drive_pin(char port, int bit, bool level) {
  const int index = port_index(port);
  if (bit < 0 || bit > 7) throw ArmctlError(ErrorKind::invalid_argument, "AvrChip: pin bit must be 0..7");
  auto& mask = driven_mask_[static_cast<std::size_t>(index)];
  auto& levels = driven_level_[static_cast<std::size_t>(index)];
  const auto bit_mask = static_cast<std::uint8_t>(1u << bit);
  const bool known = (mask & bit_mask) != 0;
  const bool old_level = (levels & bit_mask) != 0;
  mask = static_cast<std::uint8_t>(mask | bit_mask);
  levels = static_cast<std::uint8_t>(level ? (levels | bit_mask) : (levels & ~bit_mask));
  // The "external" level keeps a pin at what we drive even when the firmware rewrites the
  // port register (simavr would otherwise re-assert the internal pull-up level).
  avr_ioport_external_t ext;
  ext.name = static_cast<unsigned long>(port);
  ext.mask = mask;
  ext.value = levels;
  avr_ioctl(avr_, AVR_IOCTL_IOPORT_SET_EXTERNAL(port), &ext);
  if (known && old_level == level) return;
  avr_raise_irq(avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ(port), bit), level ? 1 : 0);
}

void AvrChip::reapply_pins() {
  const char ports[2] = {'B', 'D'};
  for (std::size_t i = 0; i < 2; ++i) {
    avr_ioport_external_t ext;
    ext.name = static_cast<unsigned long>(ports[i]);
    ext.mask = driven_mask_[i];
    ext.value = driven_level_[i];
    avr_ioctl(avr_, AVR_IOCTL_IOPORT_SET_EXTERNAL(ports[i]), &ext);
    for (int bit = 0; bit < 8; ++bit) {
      if (driven_mask_[i] & (1u << bit)) {
        avr_raise_irq(avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ(ports[i]), bit),
                      (driven_level_[i] >> bit) & 1u);
      }
    }
  }
}

void AvrChip::uart_receive(std::uint8_t byte, int index) {
  if (index < 0 || index >= model_.uart_count)
    throw ArmctlError(ErrorKind::invalid_argument, std::string("AvrChip: ") + model_.mcu + " has no UART" + std::to_string(index));
  const bool receiver_on = (avr_->data[m::ucsr0b + index * m::uart1_offset] & (1u << m::rxen0)) != 0;
  if (held_in_reset_ || !receiver_on) return;  // a disabled receiver sees nothing
  avr_uart_t* uart = uarts_[static_cast<std::size_t>(index)];
  avr_raise_irq(avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ(static_cast<char>('0' + index)), UART_IRQ_INPUT), byte);
  // simavr would flag the byte one byte time after it was handed over; the bus hands it
  // over when its stop bit ends, which is when real hardware sets RXC.
  if (!avr_regbit_get(avr_, uart->rxc.raised)) {
    uart->rxc_raise_time = avr_->cycle;
    uart->rx_cnt = 0;
    avr_raise_interrupt(avr_, &uart->rxc);
  }
}

bool AvrChip::uart_transmitter_enabled() const {
  return !held_in_reset_ && (avr_->data[m::ucsr0b] & (1u << m::txen0)) != 0;
}

bool AvrChip::uart_receiver_enabled() const {
  return (avr_->data[m::ucsr0b] & (1u << m::rxen0)) != 0;
}

std::uint8_t AvrChip::read_data(std::uint16_t address) const { return avr_->data[address]; }

bool AvrChip::output_pin(std::uint16_t ddr, std::uint16_t port, int bit) const {
  // An input pin is high-Z: the board's pull-downs hold the H-bridge inputs LOW.
  return ((avr_->data[ddr] >> bit) & 1u) != 0 && ((avr_->data[port] >> bit) & 1u) != 0;
}

BridgeInputs AvrChip::bridge_inputs() const {
  BridgeInputs in;
  if (held_in_reset_) return in;
  const std::uint8_t* d = avr_->data;
  // Left = OC1B (PB2). Timer1 in 8-bit phase-correct PWM: duty = OCR1B / 255.
  const unsigned com1b = (d[m::tccr1a] >> m::com1b0) & 3u;
  const bool pb2_output = ((d[m::ddrb] >> 2) & 1u) != 0;
  if (com1b >= 2 && pb2_output) {
    const double duty = d[m::ocr1bl] / 255.0;
    in.left = com1b == 2 ? duty : 1.0 - duty;
  } else {
    in.left = output_pin(m::ddrb, m::portb, 2) ? 1.0 : 0.0;
  }
  // Right = OC2A (PB3). Timer2 phase-correct PWM, TOP 0xFF: duty = OCR2A / 255.
  const unsigned com2a = (d[m::tccr2a] >> m::com2a0) & 3u;
  const bool pb3_output = ((d[m::ddrb] >> 3) & 1u) != 0;
  if (com2a >= 2 && pb3_output) {
    const double duty = d[m::ocr2a] / 255.0;
    in.right = com2a == 2 ? duty : 1.0 - duty;
  } else {
    in.right = output_pin(m::ddrb, m::portb, 3) ? 1.0 : 0.0;
  }
  in.enable = output_pin(m::ddrd, m::portd, 4);
  return in;
}

bool AvrChip::led() const { return !held_in_reset_ && output_pin(m::ddrb, m::portb, 5); }

}  // namespace armctl::joint_avr

// Arm controller firmware for the SCARA's Arduino Mega 2560 (16 MHz), plain avr-libc: Robot
// Commands on UART0 (the USB serial port), the joint bus on UART1 with the select lines of
// joints 1..7 on D22..D28 (PA0..PA6), as the original master is wired. The portable
// ControllerCore (src/portable_controller) does all the work; this is the main loop: bytes
// in and out, select lines, the watchdog. docs/mega-controller.md describes the whole.
//
// Build-time settings (make flash-controller RC_BAUD=... JOINT_BAUD=...):
//   ARMCTL_RC_BAUD     upstream baud (9600 default, 115200)
//   ARMCTL_JOINT_BAUD  joint bus baud (9600 default, 115200): must match the joints'
//   ARMCTL_BATTERY_ADC 0 (default): GetBatteryVoltage answers the fixed supply value of
//                      scara_arm.cpp; 1: it is measured on A0 through a 47k/10k divider
//                      (make ... BATTERY=a0; docs/mega-controller.md "Wiring")
#include <avr/eeprom.h>
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/wdt.h>

#include "board/tick_timer.hpp"
#include "mega/mega_uart.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/rc_frame_reader.hpp"
#include "portable_controller/scara_arm.hpp"

#ifndef ARMCTL_RC_BAUD
#define ARMCTL_RC_BAUD 9600UL
#endif
#ifndef ARMCTL_JOINT_BAUD
#define ARMCTL_JOINT_BAUD 9600UL
#endif
#ifndef ARMCTL_BATTERY_ADC
#define ARMCTL_BATTERY_ADC 0
#endif

namespace ctl = armctl::controller;

// The very first code after reset (.init3, before static constructors): stop a watchdog
// that survived the reset and drive every select line LOW (no joint selected), so that a
// reset mid-transaction leaves the bus idle. From reset to here every pin is a high-Z input:
// the joint boards' pull-downs hold their select inputs LOW meanwhile.
uint8_t mega_reset_cause __attribute__((section(".noinit")));
extern "C" void mega_safe_state_at_reset(void) __attribute__((naked, used, section(".init3")));
extern "C" void mega_safe_state_at_reset(void) {
  mega_reset_cause = MCUSR;
  MCUSR = 0;
  wdt_disable();
  PORTA = static_cast<uint8_t>(PORTA & 0x80u);
  DDRA = static_cast<uint8_t>(DDRA | 0x7Fu);
}

ISR(TIMER0_COMPA_vect) { board::tick_timer_count_from_isr(); }

namespace {

// Select line of joint n (1..7) = PA(n-1) = D22 + n - 1.
class MegaBus final : public ctl::BusPort {
 public:
  void set_select(uint8_t joint, bool high) override {
    const uint8_t bit = static_cast<uint8_t>(1u << (joint - 1));
    if (high) {
      PORTA = static_cast<uint8_t>(PORTA | bit);
    } else {
      lower_ = static_cast<uint8_t>(lower_ | bit);  // once the bytes queued so far are out
      mega::bus_notify_tx_done();
    }
  }
  void send_byte(uint8_t byte) override { mega::uart_send(mega::Port::bus, byte); }
  // The master runs in the bus's receive interrupt (bus_byte_received) too: every call from
  // the main loop masks interrupts while it runs (a few dozen cycles).
  uint8_t hold_rx() override {
    const uint8_t sreg = SREG;
    cli();
    return sreg;
  }
  void release_rx(uint8_t held) override { SREG = held; }
  uint32_t now_us() override { return board::tick_timer_us(); }
  // A select waiting to fall falls once the last byte before it has left: from the
  // transmitter's TX-complete interrupt (or at once), never waiting for a main-loop pass.
  void lower_pending() {
    PORTA = static_cast<uint8_t>(PORTA & ~lower_);
    lower_ = 0;
  }

 private:
  uint8_t lower_ = 0;
};

class MegaUpstream final : public ctl::UpstreamPort {
 public:
  // A reply never waits for the host: if the ring is full the rest is dropped (64-byte
  // frames into a 128-byte ring; the host reads continuously).
  void send_frame(uint8_t command, const uint8_t* data, uint8_t length) override {
    const uint8_t head[4] = {0x55, 0x55, static_cast<uint8_t>(length + 2), command};
    if (mega::uart_send_bytes(mega::Port::upstream, head, 4) == 4)
      mega::uart_send_bytes(mega::Port::upstream, data, length);
  }
};

// Action groups in the whole 4 KiB EEPROM (group_store.hpp has the layout). A byte write
// takes 3.4 ms: the store starts one only when the previous one is done, so the main loop
// never waits for the EEPROM.
class MegaEeprom final : public ctl::GroupMemory {
 public:
  uint32_t size() const override { return E2END + 1; }
  // Addresses are below size(): 16 bits hold them.
  uint8_t read(uint32_t address) override {
    return eeprom_read_byte(reinterpret_cast<const uint8_t*>(static_cast<uint16_t>(address)));
  }
  bool ready() override { return eeprom_is_ready(); }
  void write(uint32_t address, uint8_t value) override {
    eeprom_update_byte(reinterpret_cast<uint8_t*>(static_cast<uint16_t>(address)), value);
  }
};

const uint32_t joint_start_ms = 100;

MegaBus bus;
MegaUpstream upstream;
MegaEeprom eeprom;
ctl::ControllerCore core;
ctl::RcFrameReader reader;

#if ARMCTL_BATTERY_ADC
// The motor supply on A0 (PF0, ADC0) through a divider: supply -- 47 kOhm -- A0 -- 10 kOhm
// -- GND, against AVcc (5 V): A0 = supply x 10/57, full scale 5000 x 57/10 = 28,500 mV (24 V
// reads 4.21 V at the pin; 28.5 V and above read as 28,500 mV). Conversions are started
// and collected by the main loop, never waited for: 16 of them (104 us each at 125 kHz)
// make one reading, their mean in mV, about every 1.7 ms. No float, no interrupt.
class BatteryAdc {
 public:
  static const uint32_t full_scale_mv = 28500;
  static const uint8_t samples = 16;
  void begin() {
    ADMUX = _BV(REFS0);   // AVcc reference, ADC0, right adjusted
    ADCSRB = 0;           // MUX5 = 0: ADC0..7
    DIDR0 = _BV(ADC0D);   // no digital input buffer on A0
    ADCSRA = static_cast<uint8_t>(_BV(ADEN) | _BV(ADSC) | _BV(ADPS2) | _BV(ADPS1) | _BV(ADPS0));  // 16 MHz / 128
  }
  // True when a new reading is in *millivolts.
  bool service(uint16_t* millivolts) {
    if ((ADCSRA & _BV(ADSC)) != 0) return false;  // converting
    sum_ = static_cast<uint16_t>(sum_ + ADC);
    ADCSRA = static_cast<uint8_t>(ADCSRA | _BV(ADSC));
    if (++count_ < samples) return false;
    *millivolts = static_cast<uint16_t>((uint32_t(sum_) * full_scale_mv + samples * 512UL) / (samples * 1024UL));
    sum_ = 0;
    count_ = 0;
    return true;
  }

 private:
  uint16_t sum_ = 0;  // at most 16 x 1023
  uint8_t count_ = 0;
};
BatteryAdc battery;

void measure_battery() {
  uint16_t millivolts;
  if (battery.service(&millivolts)) core.set_battery_millivolts(millivolts);
}
#else
void measure_battery() {}
#endif

}  // namespace

// Each joint bus byte goes to the master at once, from UART1's receive interrupt: COMMAND
// after READY, the select fall after RESPONSE and the next poll's select after STATUS
// (BusMaster::chain) leave without waiting for a main-loop pass. The master reads the clock
// only after the byte's action (MegaBus::now_us).
void mega::bus_byte_received(uint8_t byte) { core.on_bus_byte(byte); }

// From UART1's TX-complete interrupt: a select waiting for the last byte to leave falls.
void mega::bus_tx_done() { bus.lower_pending(); }

int main() {
  board::tick_timer_begin();
  mega::uart_begin(mega::Port::upstream, ARMCTL_RC_BAUD);
  mega::uart_begin(mega::Port::bus, ARMCTL_JOINT_BAUD);
  DDRB = static_cast<uint8_t>(DDRB | _BV(PB7));  // LED D13: on while a joint is selected
  sei();
  reader.set_gap_us(ctl::frame_gap_us(ARMCTL_RC_BAUD));
  core.begin(ctl::scara_joints, ctl::scara_joint_count, &bus, &upstream, ARMCTL_JOINT_BAUD, board::tick_timer_us(),
             &eeprom);
  core.set_battery_millivolts(ctl::scara_supply_millivolts);
#if ARMCTL_BATTERY_ADC
  battery.begin();
#endif
  // Watchdog: a main loop stuck for 250 ms resets the board (selects LOW, joints halted).
  wdt_enable(WDTO_250MS);
  // After a common power-up the joints need a few ms to read their EEPROM: give them 100 ms
  // before the first transaction (upstream bytes wait in the ring meanwhile).
  // The battery is measured meanwhile (its first reading is ready long before).
  while (board::tick_timer_ms() < joint_start_ms) {
    wdt_reset();
    measure_battery();
  }
  for (;;) {
    wdt_reset();
    // Heartbeat: one write per pass to a register with no pin (one cycle), so the benchmark
    // times every pass of this loop on emulated silicon (bench_mega_controller).
    GPIOR0 = 0;
    // One clock read a pass (a pass is about 12 us), again after a request, which may
    // have planned a move (milliseconds).
    uint32_t now = board::tick_timer_us();
    uint8_t byte;
    bool framed = false;
    while (!framed && mega::uart_receive_upstream(&byte)) {
      if (reader.on_byte(byte, now)) {
        core.on_frame(reader.command(), reader.data(), reader.data_length(), now);
        framed = true;
        now = board::tick_timer_us();
      }
    }
    measure_battery();
    // A pass that handled a request (up to ~1,800 cycles for a reply of seven positions)
    // leaves the bus work to the next pass: no pass is longer than a word at 115200.
    if (!framed) core.poll(now);
    if ((PORTA & 0x7Fu) != 0) PORTB = static_cast<uint8_t>(PORTB | _BV(PB7));
    else PORTB = static_cast<uint8_t>(PORTB & ~_BV(PB7));
  }
}

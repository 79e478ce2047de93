// Joint controller firmware for the ATmega328P (Arduino Nano, 16 MHz), plain avr-libc.
// The portable JointController (src/portable) does all the work; this is the main loop:
// hand on the bus events the ISRs could not (joint_isrs.cpp), release TX when
// the joint may no longer drive it, light the LED during a transaction, feed the
// watchdog, and sleep until the next interrupt. docs/firmware.md describes the whole.
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <avr/wdt.h>
#include <util/atomic.h>

#include "board/bus_events.hpp"
#include "board/encoder_input.hpp"
#include "board/h_bridge.hpp"
#include "board/joint_config.hpp"
#include "board/reset_cause.hpp"
#include "board/select_line.hpp"
#include "board/status_led.hpp"
#include "board/tick_timer.hpp"
#include "board/uart.hpp"
#include "joint_firmware.hpp"

namespace firmware {
namespace {
// Zero-filled at start-up (.bss) instead of copied from flash (.data): begin() sets every
// field whose power-up value is not zero, and the ~150 bytes of initial values are flash
// the image does not have to spare (docs/firmware.md "Budgets").
union JointStorage {
  JointStorage() {}
  armctl::joint_bus::JointController joint;
};
JointStorage storage;
}  // namespace
armctl::joint_bus::JointController& joint = storage.joint;
volatile bool joint_running = false;
}  // namespace firmware

namespace {

using firmware::joint;

// Watchdog: the main loop feeds it only when the 1 kHz tick has moved on since the last
// feed, so a stuck main loop and a stopped tick interrupt both end in a reset (and the
// reset puts the motor in the safe state first thing: board/safe_state.cpp).
const uint8_t watchdog_timeout = WDTO_60MS;

void sleep_until_interrupt() {
  // Sleep only if nothing is waiting; the check and the sleep must not be split by an
  // interrupt, hence cli ... sei; sleep (the instruction after sei always runs first).
  cli();
  if (board::bus_events_pending() || !firmware::encoder_levels_queue.empty()) {
    sei();
    return;
  }
  sleep_enable();
  sei();
  sleep_cpu();
  sleep_disable();
}

// Unset or invalid EEPROM: never answer, motor off, LED blink code "two short flashes
// every 2 seconds" (on 150 ms, off 150 ms, on 150 ms, off 1550 ms).
[[noreturn]] void run_unconfigured() {
  board::uart_end();
  for (;;) {
    wdt_reset();
    const uint16_t phase = static_cast<uint16_t>(board::tick_timer_ms() % 2000UL);
    board::status_led_set(phase < 150 || (phase >= 300 && phase < 450));
    sleep_until_interrupt();
  }
}

// Turns the transmitter off (TX pin high-Z) once this joint may no longer drive TX and the
// last byte has left. Reply bytes themselves are moved by firmware::handle_next_bus_event.
void release_tx_when_done() {
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    joint.poll(board::tick_timer_us());
    firmware::service_tx();
  }
}

}  // namespace

int main() {
  // board_safe_state_at_reset (.init3) already put the motor outputs LOW and the
  // watchdog off.
  board::h_bridge_begin();
  board::status_led_begin();
  board::tick_timer_begin();
  wdt_enable(watchdog_timeout);
  set_sleep_mode(SLEEP_MODE_IDLE);  // timers and UART keep running in idle sleep

  board::JointConfig config = {0, 9600, armctl::joint_bus::JointOptions()};
  if (!board::joint_config_load(&config)) {
    sei();
    run_unconfigured();
  }
  armctl::joint_bus::JointTuning tuning = board::joint_tuning_load();
  if (tuning.pwm_max > 255 || tuning.pwm_max < 1) tuning.pwm_max = 255;  // 8-bit timers
  if (!joint.begin(config.joint_number, tuning, config.baud, config.options)) {
    sei();
    run_unconfigured();
  }

  board::encoder_input_begin();
  {
    const uint8_t levels = board::encoder_levels(PIND);
    joint.init_encoder((levels & 1) != 0, (levels & 2) != 0);
  }
  board::uart_begin(config.baud);
  board::select_line_begin();
  firmware::joint_running = true;
  sei();

  uint8_t fed_at_tick = board::tick_timer_ticks();
  for (;;) {
    const uint8_t tick = board::tick_timer_ticks();
    if (tick != fed_at_tick) {
      fed_at_tick = tick;
      wdt_reset();
    }
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
      firmware::apply_encoder_edges();
      // The board's own counters, for read_diagnostic (a few loads and stores).
      const armctl::joint_bus::BoardDiagnostics d = {
          {board::bus_events_lost(), firmware::encoder_edges_lost, board::uart_rx_errors(), board_reset_cause}};
      joint.set_board_diagnostics(d);
    }
    // Events the ISRs could not handle at once (they came during the control computation).
    for (;;) {
      bool handled;
      ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { handled = firmware::handle_next_bus_event(); }
      if (!handled) break;
    }
    release_tx_when_done();
    bool in_transaction;
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { in_transaction = joint.transaction().selected() || joint.tx_enabled(); }
    board::status_led_set(in_transaction || board::uart_transmitter_enabled());
    sleep_until_interrupt();
  }
}

// The interrupt handlers of the joint controller. Board code (board/) only moves bytes and
// edges; this file is where the hardware events meet the portable controller.
//
// Sharing rules (src/portable/joint_controller.hpp): every controller call is made with
// interrupts masked, or from an ISR that nothing else touching the controller can preempt.
//
// Encoder edges: the INT0/INT1 ISR only samples both channel levels (one PIND read) into a
// queue, which keeps it short enough that a burst of edges is never missed. The levels are
// handed to the decoder (JointController::on_encoder_edge), in order and with interrupts
// masked, by the main loop as soon as it wakes (every ISR wakes it) and by the control tick
// just before it runs, so control_tick() always sees every edge up to its start.
//
// Bus events: the select and UART RX ISRs queue each edge and byte, then hand the queue to
// the controller at once (board::bus_events_queued_from_isr), so READY, RESPONSE and STATUS
// go out from interrupt context instead of after the main loop wakes.
//
// The 1 kHz control tick (about 1,400 cycles) re-enables interrupts while it computes, so
// encoder edges are sampled on time and bus bytes are not delayed; none of the ISRs that
// can nest inside it touches the controller (meanwhile the bus ISRs only fill the queue,
// which the main loop then hands on), so control_tick() never sees controller state change
// under it.
#include <avr/interrupt.h>
#include <avr/io.h>

#include "board/bus_events.hpp"
#include "board/encoder_input.hpp"
#include "board/h_bridge.hpp"
#include "board/tick_timer.hpp"
#include "board/uart.hpp"
#include "joint_firmware.hpp"

namespace firmware {

board::RingBuffer<uint8_t, 32> encoder_levels_queue;
volatile uint8_t encoder_edges_lost = 0;

void apply_encoder_edges() {
  uint8_t levels;
  while (encoder_levels_queue.pop(&levels)) {
    joint.on_encoder_edge((levels & 1) != 0, (levels & 2) != 0);
  }
}

void service_tx() {
  if (joint.tx_enabled()) {
    board::uart_enable_transmitter();
    uint8_t byte;
    while (board::uart_tx_has_room() && joint.next_tx_byte(&byte)) board::uart_queue_tx(byte);
  }
  // TX released as soon as the controller lets go of it (its STATUS handed to the UART),
  // from the interrupt that handed it over too: the main loop may have gone to sleep just
  // before, and with both STATUS bytes written straight to the UART no later interrupt
  // wakes it (the next joint's READY then met this joint's TX still driven).
  if (!joint.tx_enabled()) board::uart_release_transmitter_when_idle();
}

// Out of line: one copy for the ISRs and the main loop (flash, docs/firmware.md "Budgets").
__attribute__((noinline)) bool handle_next_bus_event() {
  board::BusEvent event;
  if (!board::bus_event_pop(&event)) return false;
  const uint32_t now = board::tick_timer_us();
  apply_encoder_edges();  // a get_position answers with every edge up to now
  if (event == board::select_high_event) {
    joint.on_select(true, now);
  } else if (event == board::select_low_event) {
    joint.on_select(false, now);
  } else {
    // A get_position's RESPONSE starts before the command is executed (the same position:
    // no edge is applied in between).
    uint8_t ahead;
    if (joint.response_ahead(static_cast<uint8_t>(event), &ahead)) board::uart_send_ahead(ahead);
    joint.on_rx_byte(static_cast<uint8_t>(event), now);
  }
  service_tx();
  // A byte sent ahead whose word the controller did not queue after all (a command word
  // completed after the timeout: abandoned) leaves one stray byte on the wire, never a
  // later byte of ours left out.
  board::uart_forget_ahead();
  return true;
}

}  // namespace firmware

// The select and UART RX ISRs call this after queuing an event: the event is handled at
// once, in the ISR, so READY, RESPONSE and STATUS start without waiting for the main loop
// (the bus turnarounds, docs/firmware.md "Budgets"). Not while the control tick computes
// with interrupts enabled (OCIE0A is off exactly then: the sharing rules above); the main
// loop handles what queued meanwhile, in order, and until it has, later events queue
// behind them.
bool board::bus_byte_ahead(bool select_high, uint8_t* byte) {
  return firmware::joint.transaction().first_byte_on_select(select_high, byte);
}

bool board::bus_events_handled_in_isr() { return (TIMSK0 & _BV(OCIE0A)) != 0; }

void board::bus_events_queued_from_isr() {
  if (!board::bus_events_handled_in_isr()) return;
  while (firmware::handle_next_bus_event()) {
  }
}

// Any change on A (INT0) or B (INT1).
ISR(INT0_vect) {
  if (!firmware::encoder_levels_queue.push(board::encoder_levels(PIND))) {
    if (firmware::encoder_edges_lost != 0xFF) firmware::encoder_edges_lost = firmware::encoder_edges_lost + 1;
  }
}

ISR(INT1_vect, ISR_ALIASOF(INT0_vect));

// The 1 kHz control tick (Timer0 compare match A).
ISR(TIMER0_COMPA_vect) {
  board::tick_timer_count_from_isr();
  if (!firmware::joint_running) return;
  firmware::apply_encoder_edges();
  TIMSK0 &= static_cast<uint8_t>(~_BV(OCIE0A));  // no re-entry while interrupts are on
  sei();
  const armctl::joint_bus::DriveOutput out = firmware::joint.control_tick();
  board::h_bridge_apply(out.duty, out.enable);
  cli();
  TIMSK0 |= _BV(OCIE0A);
}

// The one joint controller this chip runs, shared by main() and the interrupt handlers.
#pragma once

#include "board/ring_buffer.hpp"
#include "portable/joint_controller.hpp"

namespace firmware {

extern armctl::joint_bus::JointController& joint;
// Set once the controller is configured; the timer ISR runs the loop only then.
extern volatile bool joint_running;

// Encoder channel levels sampled by the INT0/INT1 ISR (bit 0 = A, bit 1 = B), waiting to be
// decoded; and how many edges were lost because the queue was full (diagnostic).
extern board::RingBuffer<uint8_t, 32> encoder_levels_queue;
extern volatile uint8_t encoder_edges_lost;
// Hands the queued levels to the controller. Interrupts must be masked.
void apply_encoder_edges();
// Moves reply bytes to the UART while the controller allows this joint to drive TX (a
// byte taken from the controller is always sent in full: a word is never cut in half), and
// releases TX once it no longer does. Interrupts must be masked.
void service_tx();
// Hands the oldest queued bus event (a byte or a select edge) to the controller and moves
// its reply bytes to the UART; false if none was queued. Interrupts must be masked, and the
// control computation must not be running (the joint controller's sharing rules).
bool handle_next_bus_event();

}  // namespace firmware

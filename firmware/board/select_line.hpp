// The select line D12 (PB4), active HIGH, watched by pin-change interrupt PCINT4. Each
// edge becomes a bus event (board/bus_events.hpp) in order with the received bytes.
#pragma once

namespace board {

void select_line_begin();
bool select_line_high();

}  // namespace board

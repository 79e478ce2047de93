#include "board/bus_events.hpp"

#include "board/ring_buffer.hpp"

namespace board {
namespace {
// 16 events: 8 word times at 115200 baud of main-loop stall before anything is lost.
RingBuffer<BusEvent, 16> events;
volatile uint8_t lost = 0;
}  // namespace

void bus_event_push_from_isr(BusEvent event) {
  if (!events.push(event) && lost != 0xFF) lost = static_cast<uint8_t>(lost + 1);
}

bool bus_event_pop(BusEvent* event) { return events.pop(event); }
bool bus_events_pending() { return !events.empty(); }
uint8_t bus_events_lost() { return lost; }

}  // namespace board

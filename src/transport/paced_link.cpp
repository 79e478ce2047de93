#include "transport/paced_link.hpp"

#include <thread>

namespace armctl::transport {

namespace {
// Behind by more than this: re-anchor rather than run a burst of simulated time.
constexpr Duration kMaxLag = std::chrono::milliseconds(50);
}  // namespace

PacedLink::PacedLink(JointBusLink& simulated)
    : inner_(simulated), sim_anchor_(simulated.clock().now()), wall_anchor_(wall_.now()) {}

void PacedLink::flush() {
  inner_.flush();
  pace();
}

std::optional<std::uint8_t> PacedLink::read_byte(TimePoint deadline) {
  auto b = inner_.read_byte(deadline);
  pace();
  return b;
}

void PacedLink::pace() {
  const TimePoint due = wall_anchor_ + (inner_.clock().now() - sim_anchor_);
  const TimePoint wall = wall_.now();
  if (due > wall) {
    std::this_thread::sleep_for(due - wall);
  } else if (wall - due > kMaxLag) {
    sim_anchor_ = inner_.clock().now();
    wall_anchor_ = wall;
  }
}

bool runs_on_simulated_time(const JointBusLink& link) {
  return dynamic_cast<const SimClock*>(&link.clock()) != nullptr;
}

}  // namespace armctl::transport

// Closed-loop waiting for a move: read the servos' positions back until every one is within
// a tolerance of its target, or a deadline passes. A board may take longer than it was
// asked (the xArm stretches a move to its servos' speed limit; a servo can be blocked; the
// arm controller refuses a move for a joint that does not answer), so a host that needs
// to know where the arm is reads it back instead of sleeping for the move's time.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::robot_commands {

struct ArrivalOptions {
  // Servo units (0..1000 over 240 degrees): a servo has arrived when it is exactly at its
  // target, or within `tolerance` of it and at rest there (two reads in a row at most
  // `kSettledBand` apart), so that one gliding through the band is not taken as there.
  // 10 units = 2.4 degrees, what an LX bus servo under load holds reliably.
  int tolerance = 10;
  // Between two position reads (each read is one round trip on the link).
  Duration poll_period = std::chrono::milliseconds(20);
  // No arrival is declared before this instant (on client.clock()): pass the move's planned
  // end (when it was sent + its time), so that a servo still gliding through the tolerance
  // band towards its target is not taken as there. The default starts reading at once.
  TimePoint not_before{};
};

// Two reads this close (servo units) mean the servo is at rest (a held servo jitters by 1).
inline constexpr int kSettledBand = 1;

struct ServoArrival {
  std::uint8_t servo = 0;
  std::optional<std::uint16_t> target;  // none: "leave alone", which counts as arrived
  std::int16_t position = 0;            // as last read
  bool arrived = false;                 // at its target, or at rest within the tolerance
  bool operator==(const ServoArrival&) const = default;
};

struct ArrivalReport {
  std::vector<ServoArrival> servos;  // one per target, in the targets' order
  Duration elapsed{};                // from the call to the last read
  bool all_arrived() const;
  std::vector<ServoArrival> missed() const;  // the servos that did not arrive
};

// From options.not_before on, reads the positions of the servos in `targets` every
// poll_period on client.clock() until
// every servo with a target position has arrived (see ArrivalOptions) or `deadline` passes;
// at least one read is made even if `deadline` has passed.
// Group notifications that arrive meanwhile stay queued on the client. Returns the last
// reading, with every servo that did not arrive named; an error only when positions cannot
// be read (timeout, io, protocol: the client's error) or an argument is out of range.
Result<ArrivalReport> wait_until_arrived(Client& client, const std::vector<ServoTarget>& targets,
                                         TimePoint deadline, const ArrivalOptions& options = {});

}  // namespace armctl::robot_commands

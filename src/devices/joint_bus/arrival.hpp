// Closed-loop waiting on the joint bus: poll the joints until each has arrived, or a
// deadline passes. Two ways to say "arrived": the joint's own zone around its target
// (check_target_reached, the zone set with set_zone), or a position within a tolerance of a
// target the caller gives (get_position). A joint whose polls keep failing is reported
// with the master's error; the others are still waited for.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "devices/joint_bus/bus_master.hpp"

namespace armctl::joint_bus {

struct WaitOptions {
  // Between two sweeps of polls (each poll is one transaction per waiting joint).
  Duration poll_period = std::chrono::milliseconds(20);
  // A joint whose poll fails this many times in a row counts as failed: one lost answer
  // while polling is not worth giving up the wait for.
  int failed_polls_allowed = 3;
};

struct JointArrival {
  int joint = 0;
  bool arrived = false;
  // Why not, when not: the master's error after failed polls (with its JointFailure), or a
  // timeout error naming the position and target at the deadline.
  std::optional<Error> error;
  std::optional<std::int16_t> position;  // last read (wait_until_at; on timeout also the other)
  std::optional<std::int16_t> target;    // the target waited for (read back on timeout)
  Duration after{};                      // from the call to arrival (or giving up)
};

struct JointTarget {
  int joint = 0;
  std::int16_t position = 0;  // clicks
};

// Polls check_target_reached for `joints` until each is in its own zone, has failed, or
// `deadline` (on master.clock()) passes; one result per joint, in the order given. Joints
// not in their zone at the deadline get a timeout error with their position and target.
std::vector<JointArrival> wait_until_reached(BusMaster& master, std::span<const int> joints,
                                             TimePoint deadline, const WaitOptions& options = {});

// Polls get_position until each joint is within `tolerance` (>= 0) clicks of its target,
// has failed, or `deadline` passes; one result per target, in the order given. At least one
// sweep is made even if `deadline` has passed.
std::vector<JointArrival> wait_until_at(BusMaster& master, std::span<const JointTarget> targets,
                                        int tolerance, TimePoint deadline,
                                        const WaitOptions& options = {});

// True when every joint arrived.
bool all_arrived(std::span<const JointArrival> arrivals);

}  // namespace armctl::joint_bus

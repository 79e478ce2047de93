// What ControllerRunner serves to a host: an arm controller that takes the host's bytes and
// does its bus work one step at a time. Two implement it: ControllerDevice (the Linux
// daemon's own Board and ArmController) and CoreDevice (the portable core the Mega runs).
#pragma once

#include <cstdint>
#include <span>

#include "core/clock.hpp"

namespace armctl::arm_controller {

class ServedController {
 public:
  virtual ~ServedController() = default;
  // Bytes from the host (Robot Commands, serial form), as they arrived.
  virtual void receive(std::span<const std::uint8_t> bytes) = 0;
  // One bus step; waits no later than `limit`.
  virtual void step(TimePoint limit) = 0;
  virtual const Clock& clock() const = 0;
};

}  // namespace armctl::arm_controller

// The seam between the Arm API and a device: positions and moves in the device's own units
// (Robot Commands servo positions, joint-bus clicks), one entry per joint of the arm model,
// in the model's order. Implementations: rc_arm_device (any Robot Commands board: xArm,
// emulated xArm, armctl's arm controller) and bus_arm_device (the joint bus, via BusMaster).
// Devices validate what their protocol can carry and refuse before sending anything.
// Beyond moving joints a device may offer optional capabilities (action groups, health):
// apps ask the device for them and never reach around it to the board or bus underneath.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "arm/action_groups.hpp"
#include "arm/arm_model.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"

namespace armctl::arm {

// What a device can tell of its own health beyond positions.
struct DeviceHealth {
  std::optional<double> battery_volts;  // a board's supply
  std::vector<std::string> faults;      // "joint 3: overcurrent" (joints that report faults)
};

class ArmDevice {
 public:
  virtual ~ArmDevice() = default;
  virtual Protocol protocol() const = 0;
  virtual std::string description() const = 0;
  virtual const Clock& clock() const = 0;

  // How often a closed-loop wait may read positions (HID boards: slowly; reads during a
  // move make a real xArm's servos jerk).
  virtual Duration poll_interval() const = 0;

  // Where every joint stands, in device units.
  virtual Result<std::vector<double>> read_positions() = 0;
  // Moves the joints that have a target so that all of them arrive `duration` from now
  // (as closely as the device can); joints without a target are left alone.
  virtual Status move(const std::vector<std::optional<double>>& targets, Duration duration) = 0;
  // Stops every joint where it stands and holds it there.
  virtual Status stop() = 0;
  // Torque off: the joints can be moved by hand. On: they hold where they stand.
  virtual Status set_torque(bool on) = 0;
  // Torque off for one joint (a stalled one: arm/stall_watch.hpp); the others keep holding.
  // A device that cannot release one joint alone releases them all.
  virtual Status release(int joint) {
    (void)joint;
    return set_torque(false);
  }
  // Streaming (arm/motion_executor.hpp). The shortest interval between two stream points the
  // link carries without falling behind: the wire time of one point's frames (plus a
  // position read's, if `with_read`).
  virtual Duration stream_period(bool with_read) const = 0;
  // Time from handing a point to the link until the device acts on it (its frame's wire
  // time): the executor sends each point this much early.
  virtual Duration stream_latency() const = 0;
  // One stream point: every joint to `targets` (device units, one per joint) `in` from now,
  // arriving at `velocities` (device units/s). No read-back, no planning: the executor has
  // checked the whole motion before the first point.
  virtual Status stream(const std::vector<double>& targets, const std::vector<double>& velocities, Duration in) = 0;
  // A position read in two halves, on a device whose line is full duplex (a Robot Commands
  // board: a stream point has no reply): request_read sends the request and returns, and the
  // next read_positions returns its reply. The points streamed in between go out while the
  // reply comes back, so a loop that reads the arm back every few cycles does not hold a
  // point behind the read (arm/run_servo.cpp). read_request_time: how long the request
  // holds the outgoing line; nothing for a device that reads only whole (the default:
  // request_read is then not called).
  virtual std::optional<Duration> read_request_time() const { return std::nullopt; }
  virtual Status request_read() { return Ok{}; }
  // A device whose line is half duplex but reads every joint in a transaction of its own
  // (the joint bus): read_joint reads one joint, so that a loop can spread a read-back over
  // its cycles, one joint after each point, instead of holding the line for every joint at
  // once (arm/run_servo.cpp). joint_read_time: how long one joint's read holds the line;
  // nothing for a device that reads only whole (the default: read_joint is then not called).
  virtual std::optional<Duration> joint_read_time() const { return std::nullopt; }
  virtual Result<double> read_joint(int joint) {
    return Error{ErrorKind::invalid_argument,
                 "joint " + std::to_string(joint) + ": " + description() + " reads every joint at once"};
  }
  // Lets `d` pass on the device's clock (a simulated device runs meanwhile); an error if the
  // link failed meanwhile.
  virtual Status idle(Duration d) = 0;

  // ---- optional capabilities: nullptr / empty when the device has none
  // Action groups stored on the device (a Robot Commands board).
  virtual ActionGroups* action_groups() { return nullptr; }
  // Its health, read now (talks to the device: from the thread that owns it). What cannot be
  // read is left out.
  virtual DeviceHealth health() { return {}; }
  // Clears every joint's held faults (a joint-bus joint's runaway or following error keeps
  // its H-bridge off until then): each joint holds where it is and drives again. An error
  // names each joint that could not be cleared (one that does not answer); the others are
  // cleared all the same. A device that holds no faults (an xArm) has nothing to clear: Ok.
  virtual Status clear_faults() { return Ok{}; }
};

}  // namespace armctl::arm

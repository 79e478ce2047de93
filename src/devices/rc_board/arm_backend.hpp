// What an arm does, as seen by the board side of Robot Commands. The Board (board.hpp)
// validates every request and then calls a backend: the emulated xArm's six bus servos.
// (The SCARA's arm controller is the portable core, portable_controller/, with its own
// request handling, as on the Mega.) The Board only ever passes values it has already
// checked against what the backend reports (servo IDs present, position ranges), so
// backends need not re-validate wire input.
//
// Backends are single-threaded and driven by time: the Board passes the current time into
// every call that starts or observes motion, so tests use SimClock.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::rc_board {

using ServoId = std::uint8_t;

// The Robot Commands types, one definition each (protocol/robot_commands/messages.hpp).
// A ServoTarget without a position is "leave alone" (0xFF00 on the wire): it may be stored
// in an action, but move() never receives one: the Board and the player drop them first.
using rc::BusServoInfoReply;
using rc::BusServoLimits;
using rc::ServoMode;
using rc::ServoTarget;

// Inclusive range of positions a servo accepts as move targets.
struct PositionRange {
  std::uint16_t min = 0;
  std::uint16_t max = 1000;
  bool contains(std::uint16_t p) const { return p >= min && p <= max; }
};


class ArmBackend {
 public:
  virtual ~ArmBackend() = default;

  // IDs present, ascending. Fixed for the backend's lifetime.
  virtual std::span<const ServoId> servos() const = 0;
  bool has_servo(ServoId id) const {
    for (ServoId s : servos())
      if (s == id) return true;
    return false;
  }
  // Targets this servo accepts (its limits); a move outside is refused by the Board.
  virtual PositionRange position_range(ServoId servo) const = 0;

  // Advances the arm's own state (motion, battery) to `now`. Called by the Board before
  // every request and on every poll; `now` never goes backwards.
  virtual void advance_to(TimePoint now) = 0;

  // One synchronized move starting at `now`: every listed servo moves linearly from where
  // it is and arrives `time` later (0 = as fast as it can). Servos not listed keep what they
  // are doing. Restores torque of listed servos. Returns how long the move really takes
  // (>= time; a backend may be slower than asked when `time` is shorter than it can do),
  // or an error (device) saying why the backend refused it: then no servo moved.
  virtual Result<Duration> move(std::span<const ServoTarget> targets, Duration time,
                                TimePoint now) = 0;

  // Current position (may read slightly outside 0..1000 after offsets: signed).
  virtual std::int16_t position(ServoId servo) const = 0;
  // What the board reads back over the servo bus for ServoPositionRead / ServoOffsetRead /
  // BusServoInfoRead: nothing when no servo answered, or two did and their replies collided
  // into a frame the board cannot use (the emulated xArm with a servo ID duplicated:
  // xarm_servos.hpp). The Board then answers nothing (the protocol cannot say why).
  virtual std::optional<std::int16_t> read_position(ServoId servo) const { return position(servo); }
  virtual std::optional<std::int8_t> read_offset(ServoId servo) const { return offset(servo); }
  virtual std::optional<BusServoInfoReply> read_bus_servo_info() const { return bus_servo_info(); }

  // Removes torque (position loop off); the next move of that servo restores it.
  virtual void torque_off(std::span<const ServoId> servos) = 0;

  // Stops every servo where it is now (GroupStop).
  virtual void halt(TimePoint now) = 0;

  virtual std::uint16_t battery_millivolts() const = 0;

  // Offsets, -125..125. adjust: takes effect at once, volatile. save: persists the current
  // offset of each listed servo (may fail: I/O; then nothing changed). read: current
  // (volatile) offset.
  virtual void adjust_offset(ServoId servo, std::int8_t offset) = 0;
  virtual Status save_offsets(std::span<const ServoId> servos) = 0;
  virtual std::int8_t offset(ServoId servo) const = 0;

  // ServoSpeed: servo mode (value ignored) or motor mode turning at `speed`
  // (-1000..1000, sign = direction) until the next move, torque off or halt.
  virtual void set_mode(ServoId servo, ServoMode mode, std::int16_t speed, TimePoint now) = 0;

  // BusServoInfoRead/Write address "the servo on the bus". Which servo that is on a
  // multi-servo arm is the backend's decision (documented by each backend).
  virtual BusServoInfoReply bus_servo_info() const = 0;
  // An error (device: no such servo here; io: cannot be stored) leaves everything unchanged.
  virtual Status write_bus_servo_info(const BusServoLimits& limits) = 0;
};

}  // namespace armctl::rc_board

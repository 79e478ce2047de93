// What the calibration wizard asks of a bus of servos that keep their own ID and zero (the
// xArm's LewanSoul bus servos behind a Robot Commands board), beyond the Arm API: which IDs
// answer, a new ID for the one servo on the bus, the servo's own offset. Kept behind this
// small interface so that the wizard (calibration_session.hpp) holds no protocol: the Robot
// Commands one is rc_servo_bus.hpp; a joint bus has none (its joints are chosen by wire).
#pragma once

#include <optional>

#include "core/error.hpp"

namespace armctl::calibration {

// Servo offsets are whole units within this range (ServoOffsetAdjust: 0.24 deg each).
inline constexpr int kMaxServoOffset = 125;

class ServoBus {
 public:
  virtual ~ServoBus() = default;
  // The position servo `id` reads, or nothing when no usable answer came: no servo has the
  // ID, or two have it and their replies collided. Errors: the link itself failed.
  virtual Result<std::optional<double>> read_position(int id) = 0;
  // Gives the one servo connected to the bus ID `id`. The command carries no address: EVERY
  // servo on the bus takes the ID, so only one may be connected.
  virtual Status set_id_of_only_servo(int id) = 0;
  // The servo's own offset (-125..125 units).
  virtual Result<int> read_offset(int id) = 0;
  // Sets the offset at once (lost at power-off), then saves it in the servo.
  virtual Status adjust_offset(int id, int units) = 0;
  virtual Status save_offset(int id) = 0;
};

}  // namespace armctl::calibration

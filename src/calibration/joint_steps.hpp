// The wizard's per-joint steps as pure functions (docs/calibration.md "Steps"): what to
// change when the user says a joint went the other way, where its zero goes when it stands at
// its mark, its limits from the ends it was moved to by hand, the gripper's positions. Each
// returns a piece of CalibrationChanges (or what to do on the device), nothing is written.
#pragma once

#include <optional>
#include <string>

#include "arm/arm_model.hpp"
#include "calibration/calibration_changes.hpp"
#include "core/error.hpp"

namespace armctl::calibration {

// Limits are stored this far inside the ends the joint was moved to by hand, so that a move
// to a limit never drives the joint into its end stop: 3 deg for revolute joints, 2 mm for
// prismatic ones (a servo's deadband and a belt's stretch are below both).
inline constexpr double kLimitMarginAngle = 0.05235987755982988;  // 3 deg
inline constexpr double kLimitMarginLength = 0.002;               // 2 mm
double limit_margin(const arm::JointModel& joint);

// Where the user puts a joint for the zero step (its "mark"): its zero, or a little inside its
// travel when the zero is an end of it (the SCARA's Z), so that the hand does not press the
// joint into its end stop. Every wizard (terminal, dashboard, Python) asks for this value.
double mark_of(const arm::JointModel& joint);

// The joint was moved a small amount in its positive direction; `went_as_shown`: the user says
// it went the way the picture shows. Nothing to change when it did, else the joint's flip.
std::optional<JointChange> direction_from_answer(const arm::ArmModel& model, int joint, bool went_as_shown);

// The joint stands at its mark (torque off, or jogged there).
struct JointAtMark {
  int joint = 0;
  double reading = 0;   // the joint's value as read now (SI, the current arm file)
  // Its device position now (servo units, clicks), as the Arm API reads it: a Robot Commands
  // servo's in the commanded frame (its read-back less the offset it holds, rc_arm_device.hpp).
  double device = 0;
  double mark = 0;      // the joint's true value at the mark (SI; 0: the mark is the zero)
  // The device keeps a zero of its own: an xArm bus servo (ServoOffsetAdjust, -125..125 units).
  bool servo_offsets = false;
  int servo_offset = 0;  // the offset the servo holds now (read with ServoOffsetRead)
};

// What the wizard does to give the joint its zero.
struct ZeroStep {
  enum class Kind {
    servo_offset,  // write `servo_offset` to the servo (adjust, write, read back); the file unchanged
    file_zero,     // the arm file's zero moves: `change`
    home,          // joint bus: send `home` to the joint (its count becomes 0 where it stands), and
                   // `change` if the file must then read the mark's value at count 0
  };
  Kind kind = Kind::file_zero;
  std::optional<ServoOffset> servo_offset;
  std::optional<JointChange> change;
  std::string why;  // for people
};

// xArm (servo_offsets): the offset that makes the servo read, at the mark, the device position
// its map gives the mark, when that fits the servo's -125..125; else the file's zero. Joint
// bus: the joint's home, with a file change only when count 0 does not read as the mark (a
// coupled pair: home both, each at its mark). Otherwise the file's zero.
Result<ZeroStep> zero_at_mark(const arm::ArmModel& model, arm::Protocol protocol, const JointAtMark& at);

// Limits from the two ends the joint was moved to by hand (SI readings, either order), each
// pulled in by `margin` (limit_margin when not given). Refused: ends not finite, no travel
// left inside the margins, limits that would exclude the zero.
Result<PositionRange> limits_from_ends(const arm::ArmModel& model, int joint, double end_a, double end_b,
                                       std::optional<double> margin = std::nullopt);

// The gripper's open and closed positions from its readings there. Refused: no gripper,
// readings not finite, or too close to tell open from closed (less than twice the margin).
Result<GripperPositions> gripper_from_readings(const arm::ArmModel& model, double open, double closed);

}  // namespace armctl::calibration

// Everything a calibration changes in an arm file, as one value (docs/calibration.md "What is
// written"): per joint a direction flip, a zero shift and position limits; the gripper's open
// and closed positions; link lengths. xArm servo offsets ride along for the wizard to write
// to the servos (ServoOffsetAdjust, ServoOffsetWrite, read back): they never reach the file.
// Checked as a whole against the model (check_changes) before anything is written; the
// arm-file text is made from the checked value by a pure function (apply_changes).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arm/arm_calibration.hpp"
#include "arm/arm_model.hpp"
#include "core/error.hpp"
#include "motion/urdf_chain.hpp"

namespace armctl::calibration {

struct PositionRange {
  double lower = 0, upper = 0;  // rad or m
};

// One joint's change. The joint reads `(flip ? -1 : 1) * reading + zero_shift` from now on:
// a flip turns the reading about the joint's present zero (the device value of the zero
// stays), the shift moves the zero. `limits` are in the new readings; left out, the old
// ones carried over (flipped and shifted with the readings, kept within the URDF's limits
// and the device's range).
struct JointChange {
  std::string joint;  // its name in the arm file
  bool flip = false;
  double zero_shift = 0;
  std::optional<PositionRange> limits;
};

// An xArm servo's own offset (ServoOffsetAdjust units, -125..125, 0.24 deg each), which the
// wizard writes to the servo itself.
struct ServoOffset {
  std::string joint;
  int servo = 0;  // the servo's ID
  int units = 0;
};

struct GripperPositions {
  double open = 0, closed = 0;  // rad or m, in the gripper joint's (new) readings
};

struct CalibrationChanges {
  std::vector<JointChange> joints;
  std::optional<GripperPositions> gripper;
  std::vector<motion::OriginLength> link_lengths;  // replace these; others stay as they are
  std::vector<ServoOffset> servo_offsets;
  bool empty() const { return joints.empty() && !gripper && link_lengths.empty() && servo_offsets.empty(); }
};

// A joint's change resolved against the model: its new map for every protocol and its new
// limits.
struct CheckedJoint {
  int index = 0;
  std::map<std::string, arm::DeviceMap, std::less<>> devices;
  arm::JointLimits limits;
};

struct CheckedChanges {
  CalibrationChanges changes;
  std::vector<CheckedJoint> joints;
  std::vector<motion::OriginLength> link_lengths;  // every length the file holds afterwards
  // The gripper's positions afterwards: the new ones, or the old ones flipped and shifted
  // with the gripper joint's readings; empty when neither changes.
  std::optional<GripperPositions> gripper;
};

// Checks the whole of `changes` against `model`; invalid_argument naming the joint and what is
// allowed: an unknown or twice-named joint; a flip of one joint of a coupled pair (a coupling
// mixes two actuators: flip both or neither); a shift that is not finite; limits that are
// empty, exclude the zero, reach beyond the URDF's limits or the device's range; gripper
// positions outside the gripper's limits; a link length for an origin without offset or not
// above zero; a servo offset outside -125..125, on a joint without a Robot Commands map, or
// on a joint whose zero the file also shifts.
Result<CheckedChanges> check_changes(const arm::ArmModel& model, const CalibrationChanges& changes);

// The arm file's document with the checked changes made (the servo offsets left out): maps
// and limits of the changed joints, the gripper, the "link_lengths" section. Everything else
// is kept. invalid_config when the document lacks a joint the model has.
Result<nlohmann::json> apply_changes(nlohmann::json document, const arm::ArmModel& model,
                                     const CheckedChanges& checked);

// `armctl arm calibrate zero`'s changes (arm/arm_calibration.hpp: where the joints stand
// becomes their zero) as calibration changes, so that the wizard can take them with its other
// changes through write_calibration. A coupled pair's shifts, which calibrate_zero gives per
// actuator, become the joints' shifts through the coupling's inverse.
CalibrationChanges from_zero_changes(const arm::ArmModel& model, const std::vector<arm::ZeroChange>& zeros);

// A quantity as the arm files write it: "12.345678deg", "97.650000mm".
std::string quantity_text(Dimension dimension, double si);

}  // namespace armctl::calibration

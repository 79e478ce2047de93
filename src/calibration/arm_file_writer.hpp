// Writes calibration changes into the arm file (docs/calibration.md "What is written"): the
// only I/O of the calibration layer. The new text is made and checked as a whole (parsed
// again as an arm file with its URDF) before anything is written; then the file as it was is
// kept beside it as "<arm file>.prev" and the new text replaces the file in one atomic
// replacement (core/atomic_file.hpp). A failure before the replacement leaves the arm file
// as it was (and .prev, if written, a copy of it).
#pragma once

#include <filesystem>

#include "arm/arm_model.hpp"
#include "calibration/calibration_changes.hpp"
#include "core/error.hpp"

namespace armctl::calibration {

// "xarm.arm.json" -> "xarm.arm.json.prev".
std::filesystem::path previous_file(const std::filesystem::path& arm_file);

// Checks `changes` against `model` (check_changes), applies them to model.file's current
// content, checks the result loads, keeps the old file as previous_file(model.file) and
// replaces model.file. Servo offsets are not written (the wizard writes them to the servos).
// Returns the model loaded from the new file.
Result<arm::ArmModel> write_calibration(const arm::ArmModel& model, const CalibrationChanges& changes);

}  // namespace armctl::calibration

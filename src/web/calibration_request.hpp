// Request bodies of the calibration endpoints (POST /api/v1/calibration/STEP,
// docs/http-api.md "Calibration"): one parser for every step, strict like the others
// (web/request_body.hpp): unknown fields refused, every value checked, the error an ApiError
// 400 naming the field, the value and what is allowed. Values as the API takes them (deg or
// mm, the tool in mm), returned in SI for the engine. Pure; fuzzed with the other bodies.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arm/arm_model.hpp"
#include "web/request_body.hpp"

namespace armctl::web {

// The steps, in the wizard's order, then the session's own calls.
inline const std::vector<std::string> kCalibrationSteps{"start", "find",   "wiggle", "which",  "nudge",  "direction",
                                                        "release", "hold", "read",   "zero",   "limits", "gripper",
                                                        "touch",  "verify", "fit",   "forget", "confirm", "cancel"};

struct CalibrationRequest {
  std::string step;
  int joint = -1;                 // wiggle, which, nudge, direction, read, zero, limits; forget (-1: all)
  int moved = -1;                 // which: the joint the user saw move
  bool went_as_shown = true;      // direction
  std::optional<double> mark;     // zero: the joint's true value at its mark, SI (default: calibration::mark_of)
  double end_a = 0, end_b = 0;    // limits: readings at the two ends, SI
  double open = 0, closed = 0;    // gripper: readings open and closed, SI
  std::string name;               // touch: the point's name
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // touch: where it is (m, base frame)
  bool servo_offsets = true;      // start: zeros into the xArm servos' own offsets when they fit
};

// `step` from the URL (one of kCalibrationSteps, else 404 is the router's: here 400), `body`
// its JSON object; joints by name (the model's) or 0-based index.
CalibrationRequest parse_calibration_request(const arm::ArmModel& model, const std::string& step, const json& body);

}  // namespace armctl::web

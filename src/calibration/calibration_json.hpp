// The calibration session's results as plain JSON values, for the apps that hand them on as
// data: the HTTP API answers them (docs/http-api.md "Calibration") and the Python module gives
// them as dicts (docs/python.md "Calibration"), so that both name every field alike. SI units
// (rad or m) as everywhere in armctl; `text` fields are for people.
#pragma once

#include <nlohmann/json.hpp>

#include "calibration/calibration_session.hpp"

namespace armctl::calibration {

nlohmann::json to_json(const arm::ArmModel& model, const FindReport& report);
nlohmann::json to_json(const ZeroResult& zero);
nlohmann::json to_json(const PositionRange& range);        // {lower, upper}
nlohmann::json to_json(const GripperPositions& gripper);   // {open, closed}
nlohmann::json to_json(const NamedPoint& point);           // {name, position: [x, y, z]}
nlohmann::json to_json(const TouchedPoint& point);         // {name, position, joints}
nlohmann::json to_json(const ResidualReport& report);      // {points: [{name, error, distance}], rms, max, worst}
nlohmann::json to_json(const FitResult& fit);              // {estimates, before, after, condition, iterations}
nlohmann::json to_json(const CalibrationChanges& changes); // {joints, servo_offsets, gripper, link_lengths, empty}
// What confirm() wrote: {file, previous}.
nlohmann::json written_json(const arm::ArmModel& written);

}  // namespace armctl::calibration

// The calibration session's results as plain JSON values, for the apps that hand them on as
// data: the HTTP API answers them (docs/http-api.md "Calibration") and the Python module gives
// them as dicts (docs/calibration.md "Python"), so that both name every field alike. Values in
// `Units::si` (rad, m: Python, as everywhere in armctl's APIs) or `Units::display` (deg, mm:
// the HTTP API's convention, docs/http-api.md "Conventions"); `text` fields are for people.
#pragma once

#include <nlohmann/json.hpp>

#include "calibration/calibration_session.hpp"

namespace armctl::calibration {

enum class Units { si, display };

// Values of one arm in one kind of units: a joint's value in its own dimension, lengths
// (points, residuals, link lengths) as lengths.
class JsonValues {
 public:
  JsonValues(const arm::ArmModel& model, Units units) : model_(model), units_(units) {}
  double joint(int joint, double si) const;
  double joint(const std::string& name, double si) const;
  double length(double si) const;
  nlohmann::json point(const Eigen::Vector3d& si) const;  // [x, y, z]
  const arm::ArmModel& model() const { return model_; }

 private:
  const arm::ArmModel& model_;
  Units units_;
};

nlohmann::json to_json(const JsonValues& v, const FindReport& report);  // positions: device units as read
nlohmann::json to_json(const JsonValues& v, int joint, const ZeroResult& zero);
nlohmann::json to_json(const JsonValues& v, int joint, const PositionRange& range);  // {lower, upper}
nlohmann::json to_json(const JsonValues& v, const GripperPositions& gripper);        // {open, closed}
nlohmann::json to_json(const JsonValues& v, const NamedPoint& point);               // {name, position: [x, y, z]}
nlohmann::json to_json(const JsonValues& v, const TouchedPoint& point);             // {name, position, joints}
nlohmann::json to_json(const JsonValues& v, const ResidualReport& report);  // {points: [{name, error, distance}], rms, max, worst}
nlohmann::json to_json(const JsonValues& v, const FitResult& fit);          // {estimates: [{parameter, kind, joint, correction, uncertainty, length}], before, after, condition, iterations}
nlohmann::json to_json(const JsonValues& v, const CalibrationChanges& changes);  // {joints, servo_offsets, gripper, link_lengths, empty}
// What confirm() wrote: {file, previous}.
nlohmann::json written_json(const arm::ArmModel& written);

}  // namespace armctl::calibration

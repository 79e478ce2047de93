#include "calibration/calibration_json.hpp"

#include "calibration/arm_file_writer.hpp"

namespace armctl::calibration {

using json = nlohmann::json;

namespace {

json vec3(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

const char* kind_name(ZeroStep::Kind k) {
  switch (k) {
    case ZeroStep::Kind::servo_offset: return "servo_offset";
    case ZeroStep::Kind::home: return "home";
    case ZeroStep::Kind::file_zero: break;
  }
  return "file_zero";
}

}  // namespace

json to_json(const arm::ArmModel& model, const FindReport& report) {
  json devices = json::array();
  for (const DeviceAnswer& d : report.devices) {
    const auto joint = model.find_joint(d.joint);
    devices.push_back({{"id", d.id},
                       {"joint", d.joint},
                       {"index", joint ? json(*joint) : json(nullptr)},
                       {"answers", d.answers},
                       {"position", d.position ? json(*d.position) : json(nullptr)}});
  }
  return {{"devices", devices}, {"silent", report.silent}, {"text", report.text}};
}

json to_json(const ZeroResult& zero) {
  return {{"kind", kind_name(zero.kind)}, {"shift", zero.shift}, {"servo_offset", zero.servo_offset}, {"text", zero.text}};
}

json to_json(const PositionRange& range) { return {{"lower", range.lower}, {"upper", range.upper}}; }

json to_json(const GripperPositions& gripper) { return {{"open", gripper.open}, {"closed", gripper.closed}}; }

json to_json(const NamedPoint& point) { return {{"name", point.name}, {"position", vec3(point.position)}}; }

json to_json(const TouchedPoint& point) {
  return {{"name", point.name}, {"position", vec3(point.position)}, {"joints", point.joints}};
}

json to_json(const ResidualReport& report) {
  json points = json::array();
  for (const PointResidual& p : report.points)
    points.push_back({{"name", p.name}, {"error", vec3(p.error)}, {"distance", p.distance}});
  return {{"points", points}, {"rms", report.rms}, {"max", report.max}, {"worst", report.worst}};
}

json to_json(const FitResult& fit) {
  json estimates = json::array();
  for (const ParameterEstimate& e : fit.estimates)
    estimates.push_back({{"parameter", e.parameter.name},
                         {"kind", e.parameter.kind == ParameterKind::zero ? "zero" : "length"},
                         {"correction", e.correction},
                         {"uncertainty", e.uncertainty},
                         {"length", e.length}});
  return {{"estimates", estimates},
          {"before", to_json(fit.before)},
          {"after", to_json(fit.after)},
          {"condition", fit.condition},
          {"iterations", fit.iterations}};
}

json to_json(const CalibrationChanges& changes) {
  json joints = json::array();
  for (const JointChange& j : changes.joints)
    joints.push_back({{"joint", j.joint},
                      {"flip", j.flip},
                      {"zero_shift", j.zero_shift},
                      {"limits", j.limits ? to_json(*j.limits) : json(nullptr)}});
  json offsets = json::array();
  for (const ServoOffset& o : changes.servo_offsets)
    offsets.push_back({{"joint", o.joint}, {"servo", o.servo}, {"units", o.units}});
  json lengths = json::array();
  for (const motion::OriginLength& l : changes.link_lengths) lengths.push_back({{"joint", l.joint}, {"length", l.length}});
  return {{"joints", joints},
          {"servo_offsets", offsets},
          {"gripper", changes.gripper ? to_json(*changes.gripper) : json(nullptr)},
          {"link_lengths", lengths},
          {"empty", changes.empty()}};
}

json written_json(const arm::ArmModel& written) {
  return {{"file", written.file.string()}, {"previous", previous_file(written.file).string()}};
}

}  // namespace armctl::calibration

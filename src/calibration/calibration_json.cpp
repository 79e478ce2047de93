#include "calibration/calibration_json.hpp"

#include "calibration/arm_file_writer.hpp"
#include "core/quantity.hpp"

namespace armctl::calibration {

using json = nlohmann::json;

namespace {

const char* kind_name(ZeroStep::Kind k) {
  switch (k) {
    case ZeroStep::Kind::servo_offset: return "servo_offset";
    case ZeroStep::Kind::home: return "home";
    case ZeroStep::Kind::file_zero: break;
  }
  return "file_zero";
}

}  // namespace

double JsonValues::joint(int joint, double si) const {
  if (units_ == Units::si) return si;
  return to_display(model_.joints[std::size_t(joint)].dimension, si);
}

double JsonValues::joint(const std::string& name, double si) const {
  const auto i = model_.find_joint(name);
  return i ? joint(*i, si) : si;
}

double JsonValues::length(double si) const { return units_ == Units::si ? si : to_display(Dimension::length, si); }

json JsonValues::point(const Eigen::Vector3d& si) const { return json::array({length(si.x()), length(si.y()), length(si.z())}); }

json to_json(const JsonValues& v, const FindReport& report) {
  json devices = json::array();
  for (const DeviceAnswer& d : report.devices) {
    const auto joint = v.model().find_joint(d.joint);
    devices.push_back({{"id", d.id},
                       {"joint", d.joint},
                       {"index", joint ? json(*joint) : json(nullptr)},
                       {"answers", d.answers},
                       {"position", d.position ? json(*d.position) : json(nullptr)}});
  }
  return {{"devices", devices}, {"silent", report.silent}, {"text", report.text}};
}

json to_json(const JsonValues& v, int joint, const ZeroResult& zero) {
  return {{"kind", kind_name(zero.kind)},
          {"shift", v.joint(joint, zero.shift)},
          {"servo_offset", zero.servo_offset},
          {"text", zero.text}};
}

json to_json(const JsonValues& v, int joint, const PositionRange& range) {
  return {{"lower", v.joint(joint, range.lower)}, {"upper", v.joint(joint, range.upper)}};
}

json to_json(const JsonValues& v, const GripperPositions& gripper) {
  const int g = v.model().gripper ? v.model().gripper->joint : 0;
  return {{"open", v.joint(g, gripper.open)}, {"closed", v.joint(g, gripper.closed)}};
}

json to_json(const JsonValues& v, const NamedPoint& point) { return {{"name", point.name}, {"position", v.point(point.position)}}; }

json to_json(const JsonValues& v, const TouchedPoint& point) {
  json joints = json::array();
  for (std::size_t i = 0; i < point.joints.size(); ++i) joints.push_back(v.joint(int(i), point.joints[i]));
  return {{"name", point.name}, {"position", v.point(point.position)}, {"joints", joints}};
}

json to_json(const JsonValues& v, const ResidualReport& report) {
  json points = json::array();
  for (const PointResidual& p : report.points)
    points.push_back({{"name", p.name}, {"error", v.point(p.error)}, {"distance", v.length(p.distance)}});
  return {{"points", points}, {"rms", v.length(report.rms)}, {"max", v.length(report.max)}, {"worst", report.worst}};
}

json to_json(const JsonValues& v, const FitResult& fit) {
  json estimates = json::array();
  for (const ParameterEstimate& e : fit.estimates) {
    const bool zero = e.parameter.kind == ParameterKind::zero;
    estimates.push_back({{"parameter", e.parameter.name},
                         {"kind", zero ? "zero" : "length"},
                         // the joint whose zero it is, or the URDF joint whose origin's length
                         {"joint", zero ? v.model().joints[std::size_t(e.parameter.joint)].name : e.parameter.origin},
                         {"correction", zero ? v.joint(e.parameter.joint, e.correction) : v.length(e.correction)},
                         {"uncertainty", zero ? v.joint(e.parameter.joint, e.uncertainty) : v.length(e.uncertainty)},
                         {"length", v.length(e.length)}});
  }
  return {{"estimates", estimates},
          {"before", to_json(v, fit.before)},
          {"after", to_json(v, fit.after)},
          {"condition", fit.condition},
          {"iterations", fit.iterations}};
}

json to_json(const JsonValues& v, const CalibrationChanges& changes) {
  json joints = json::array();
  for (const JointChange& j : changes.joints) {
    json limits = nullptr;
    if (j.limits) limits = {{"lower", v.joint(j.joint, j.limits->lower)}, {"upper", v.joint(j.joint, j.limits->upper)}};
    joints.push_back({{"joint", j.joint}, {"flip", j.flip}, {"zero_shift", v.joint(j.joint, j.zero_shift)}, {"limits", limits}});
  }
  json offsets = json::array();
  for (const ServoOffset& o : changes.servo_offsets)
    offsets.push_back({{"joint", o.joint}, {"servo", o.servo}, {"units", o.units}});
  json lengths = json::array();
  for (const motion::OriginLength& l : changes.link_lengths)
    lengths.push_back({{"joint", l.joint}, {"length", v.length(l.length)}});
  return {{"joints", joints},
          {"servo_offsets", offsets},
          {"gripper", changes.gripper ? to_json(v, *changes.gripper) : json(nullptr)},
          {"link_lengths", lengths},
          {"empty", changes.empty()}};
}

json written_json(const arm::ArmModel& written) {
  return {{"file", written.file.string()}, {"previous", previous_file(written.file).string()}};
}

}  // namespace armctl::calibration

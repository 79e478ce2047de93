#include "calibration/calibration_chain.hpp"

#include <fmt/core.h>

namespace armctl::calibration {

namespace {

Eigen::Matrix3d rpy_matrix(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// Below a micrometre an origin has no offset to lengthen (as motion::apply_origin_lengths).
constexpr double kNoOffset = 1e-6;

}  // namespace

Parameter zero_parameter(const arm::ArmModel& model, int joint) {
  return Parameter{ParameterKind::zero, joint, "", fmt::format("zero of {}", model.joints[std::size_t(joint)].name)};
}

Parameter length_parameter(std::string origin) {
  std::string name = fmt::format("length of {}'s origin", origin);
  return Parameter{ParameterKind::length, -1, std::move(origin), std::move(name)};
}

Result<CalibrationChain> CalibrationChain::make(const arm::ArmModel& model) {
  if (!model.chain || !model.kinematics)
    return Error{ErrorKind::invalid_argument, "the arm model has no kinematic chain (not loaded from an arm file)"};
  const motion::UrdfChain& chain = *model.chain;
  CalibrationChain out;
  out.joint_count_ = static_cast<int>(chain.joints.size());
  auto add_fixed = [&](std::size_t before) {
    for (const motion::FixedChainJoint& f : chain.fixed) {
      if (f.before != before) continue;
      Segment s;
      s.origin = f.name;
      s.transform = f.origin;
      const double n = f.origin.translation().norm();
      if (n > kNoOffset) s.direction = f.origin.translation() / n;
      out.segments_.push_back(s);
    }
  };
  for (std::size_t i = 0; i < chain.joints.size(); ++i) {
    add_fixed(i);
    const motion::ChainJoint& j = chain.joints[i];
    Segment s;
    s.origin = j.name;
    s.transform.linear() = rpy_matrix(j.origin_rpy);
    s.transform.translation() = j.origin_xyz;
    const double n = j.origin_xyz.norm();
    if (n > kNoOffset) s.direction = j.origin_xyz / n;
    s.joint = static_cast<int>(i);
    s.revolute = j.type == motion::ChainJointType::revolute;
    s.axis = j.axis;
    out.segments_.push_back(s);
  }
  add_fixed(chain.joints.size());
  out.tool_ = model.tool.position;
  for (int i = 0; i < out.joint_count_; ++i)
    if (chain.joints[std::size_t(i)].type == motion::ChainJointType::revolute)
      out.candidates_.push_back(zero_parameter(model, i));
  for (auto it = out.segments_.rbegin(); it != out.segments_.rend(); ++it)
    if (!it->direction.isZero()) out.candidates_.push_back(length_parameter(it->origin));
  for (int i = 0; i < out.joint_count_; ++i)
    if (chain.joints[std::size_t(i)].type == motion::ChainJointType::prismatic)
      out.candidates_.push_back(zero_parameter(model, i));
  return out;
}

double CalibrationChain::length(const std::string& origin) const {
  for (const Segment& s : segments_)
    if (s.origin == origin) return s.transform.translation().norm();
  return -1;
}

Eigen::Vector3d CalibrationChain::tool_point(const Eigen::VectorXd& q, const std::vector<Parameter>& parameters,
                                             const Eigen::VectorXd& values) const {
  // Corrections by segment: a length change moves everything after the origin along its
  // offset; a zero is added to the joint's reading.
  Eigen::VectorXd joints = q;
  std::vector<double> stretch(segments_.size(), 0.0);
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    const Parameter& p = parameters[k];
    if (p.kind == ParameterKind::zero) {
      joints[p.joint] += values[Eigen::Index(k)];
    } else {
      for (std::size_t s = 0; s < segments_.size(); ++s)
        if (segments_[s].origin == p.origin) stretch[s] += values[Eigen::Index(k)];
    }
  }
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const Segment& seg = segments_[s];
    Eigen::Isometry3d origin = seg.transform;
    origin.translation() += stretch[s] * seg.direction;
    t = t * origin;
    if (seg.joint < 0) continue;
    const double v = joints[seg.joint];
    if (seg.revolute) t.rotate(Eigen::AngleAxisd(v, seg.axis));
    else t.translate(v * seg.axis);
  }
  return t * tool_;
}

}  // namespace armctl::calibration

#include "arm/sim_truth.hpp"

#include <fmt/core.h>

namespace armctl::arm {

namespace {

Eigen::Matrix3d rpy_rotation(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

Result<motion::UrdfChain> apply_link_errors(motion::UrdfChain chain, const Miscalibration& miscal) {
  for (const LinkError& e : miscal.links) {
    auto it = std::find_if(chain.joints.begin(), chain.joints.end(),
                           [&](const motion::ChainJoint& j) { return j.name == e.joint; });
    if (it == chain.joints.end() || it->origin_xyz.norm() == 0)
      return Error{ErrorKind::invalid_argument,
                   fmt::format("miscalibration {}: link error on '{}', which is no moving joint with an origin "
                               "of some length on the chain {} -> {}",
                               miscal.seed, e.joint, chain.base_link, chain.tip_link)};
    // from_previous = fixed joints * T(origin) * R(origin): lengthening the origin by d along
    // its direction u adds T(R^T * d * u) on the right.
    const Eigen::Vector3d along = it->origin_xyz.normalized() * (e.error_mm / 1000.0);
    it->from_previous = it->from_previous * Eigen::Translation3d(rpy_rotation(it->origin_rpy).transpose() * along);
    it->origin_xyz += along;
  }
  return chain;
}

Eigen::Isometry3d chain_forward(const motion::UrdfChain& chain, std::span<const double> q) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < chain.joints.size(); ++i) {
    const motion::ChainJoint& j = chain.joints[i];
    t = t * j.from_previous;
    if (j.type == motion::ChainJointType::revolute)
      t = t * Eigen::AngleAxisd(q[i], j.axis.normalized());
    else
      t = t * Eigen::Translation3d(j.axis.normalized() * q[i]);
  }
  return t * chain.tip_from_last;
}

Result<SimTruth> SimTruth::make(ArmModel shipped, Protocol protocol, Miscalibration miscal) {
  for (const JointModel& j : shipped.joints) {
    const DeviceMap* map = j.map(protocol);
    if (map == nullptr || map->id < 1 || map->id > int(miscal.joints.size()))
      return Error{ErrorKind::invalid_argument,
                   fmt::format("arm '{}': joint {} has no {} ID the miscalibration ({} devices) knows", shipped.name,
                               j.name, to_string(protocol), miscal.joints.size())};
  }
  auto chain = apply_link_errors(*shipped.chain, miscal);
  if (!chain) return chain.error();
  return SimTruth(std::move(shipped), protocol, std::move(miscal), std::move(*chain));
}

std::vector<double> SimTruth::joints(std::span<const double> true_device_by_id) const {
  std::vector<double> device;
  for (const JointModel& j : model_.joints) {
    const auto id = std::size_t(j.map(protocol_)->id);
    if (id > true_device_by_id.size())
      throw ArmctlError(ErrorKind::invalid_argument,
                        fmt::format("true device positions: {} given, joint {} has ID {}", true_device_by_id.size(),
                                    j.name, id));
    device.push_back(true_device_by_id[id - 1]);
  }
  return model_.from_device(protocol_, device);
}

motion::Pose SimTruth::tool_pose(const std::vector<double>& true_joints) const {
  std::vector<double> chain(true_joints.begin(), true_joints.begin() + model_.chain_joints());
  const Eigen::Isometry3d tip = chain_forward(chain_, chain);
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
  tool.linear() = model_.tool.orientation.toRotationMatrix();
  tool.translation() = model_.tool.position;
  const Eigen::Isometry3d t = tip * tool;
  motion::Pose pose;
  pose.position = t.translation();
  pose.orientation = Eigen::Quaterniond(t.linear());
  return pose;
}

std::vector<double> SimTruth::true_device_positions(const std::vector<double>& true_joints) const {
  const std::vector<double> truth = model_.to_device(protocol_, true_joints);
  std::vector<double> out(miscal_.joints.size(), miscal_.pivot);
  for (std::size_t i = 0; i < model_.joints.size(); ++i) out[std::size_t(model_.joints[i].map(protocol_)->id - 1)] = truth[i];
  return out;
}

std::vector<double> SimTruth::device_positions(const std::vector<double>& true_joints) const {
  std::vector<double> out = true_device_positions(true_joints);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = miscal_.device_position(int(i + 1), out[i]);
  return out;
}

}  // namespace armctl::arm

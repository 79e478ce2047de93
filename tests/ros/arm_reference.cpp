#include "arm_reference.hpp"

#include <chrono>

#include "arm/arm_model.hpp"
#include "session/arm_session.hpp"

namespace armctl::ros_test {

namespace {

arm::ArmModel model(const std::string& name) {
  return arm::load_arm_model(arm::arm_file_path(name)).value();
}

std::vector<double> flat(const motion::Pose& p) {
  return {p.position.x(), p.position.y(), p.position.z(), p.orientation.w(), p.orientation.x(), p.orientation.y(),
          p.orientation.z()};
}

}  // namespace

std::vector<ReferenceJoint> reference_joints(const std::string& arm) {
  std::vector<ReferenceJoint> out;
  for (const auto& j : model(arm).joints)
    out.push_back({j.name, j.limits.lower, j.limits.upper, j.limits.velocity, j.role == arm::JointRole::chain,
                   j.dimension == Dimension::angle});
  return out;
}

std::vector<double> reference_tool_pose(const std::string& arm, const std::vector<double>& positions) {
  const auto m = model(arm);
  motion::JointVector q(m.chain_joints());
  for (int i = 0; i < m.chain_joints(); ++i) q[i] = positions.at(std::size_t(i));
  const motion::Pose link = m.kinematics->forward(q);
  motion::Pose tool;
  tool.position = link.position + link.orientation * m.tool.position;
  tool.orientation = link.orientation * m.tool.orientation;
  return flat(tool);
}

double reference_read_seconds(const std::string& arm, int reads) {
  session::SessionOptions o;
  o.wall_clock = true;
  auto s = session::open_arm_session(arm, "", o).value();
  (void)s->arm->read().value();  // the first read may wake the link up
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < reads; ++i) (void)s->arm->read().value();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / reads;
}

std::vector<double> reference_tool_offset(const std::string& arm) { return flat(model(arm).tool); }

}  // namespace armctl::ros_test

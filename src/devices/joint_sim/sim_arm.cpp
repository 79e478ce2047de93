#include "devices/joint_sim/sim_arm.hpp"

#include <string>

#include "core/error.hpp"

namespace armctl::joint_sim {

SimArm::SimArm(ArmConfig config, SimArmOptions options)
    : config_(std::move(config)), options_(options) {
  int lines = 0;
  for (const JointConfig& j : config_.joints) lines = std::max(lines, int(j.number));
  joints_.resize(static_cast<std::size_t>(lines));
  std::vector<BusEndpoint*> endpoints(static_cast<std::size_t>(lines), nullptr);
  for (const JointConfig& j : config_.joints) {
    auto joint = std::make_unique<SimJoint>(j.number, j.tuning, config_.baud, j.hardware, TimePoint{},
                                            options_.joints);
    endpoints[j.number - 1u] = joint.get();
    joints_[j.number - 1u] = std::move(joint);
  }
  bus_ = std::make_unique<SimBus>(config_.baud, std::move(endpoints));
}

void SimArm::set_obstacle(std::function<bool(std::span<const double>)> touches) {
  if (!touches) {
    bus_->set_watch(Duration{0}, {});
    contact_.reset();
    return;
  }
  std::vector<JointHardware*> hardware;
  for (auto& j : joints_) hardware.push_back(j ? &j->hardware() : nullptr);
  contact_ = std::make_unique<ContactStop>(std::move(touches), std::move(hardware));
  bus_->set_watch(std::chrono::milliseconds(1), [this](TimePoint) { contact_->check(); });
}

std::unique_ptr<SimArm> SimArm::from_default_config() {
  return std::make_unique<SimArm>(load_arm_config(default_arm_config_path()));
}

SimJoint& SimArm::joint(int number) {
  if (number < 1 || number > joint_count() || !joints_[std::size_t(number - 1)]) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "simulated arm: no joint " + std::to_string(number) + " (allowed: 1.." +
                          std::to_string(joint_count()) + ")");
  }
  bus_->sync();
  return *joints_[std::size_t(number - 1)];
}

}  // namespace armctl::joint_sim

#include "devices/joint_sim/sim_arm.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace armctl::joint_sim {

SimArm::SimArm(ArmConfig config, SimArmOptions options)
    : config_(std::move(config)), options_(options) {
  int lines = 0;
  for (const JointConfig& j : config_.joints) lines = std::max(lines, int(j.number));
  joints_.resize(static_cast<std::size_t>(lines));
  std::vector<BusEndpoint*> endpoints(static_cast<std::size_t>(lines), nullptr);
  if (options_.miscal && options_.miscal->arm != MiscalArm::scara)
    throw ArmctlError(ErrorKind::invalid_argument, "simulated arm: a miscalibration for the xArm given to the SCARA");
  for (const JointConfig& j : config_.joints) {
    JointHardwareParams hardware = j.hardware;
    if (options_.miscal && hardware.end_stops) {
      // The stops are where they are physically; the encoder counts them from elsewhere.
      const Miscalibration& m = *options_.miscal;
      const double a = m.device_position(j.number, hardware.end_stops->min_clicks);
      const double b = m.device_position(j.number, hardware.end_stops->max_clicks);
      hardware.end_stops = EndStops{static_cast<std::int32_t>(std::ceil(std::min(a, b))),
                                    static_cast<std::int32_t>(std::floor(std::max(a, b)))};
    }
    auto joint = std::make_unique<SimJoint>(j.number, j.tuning, config_.baud, hardware, TimePoint{},
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
  if (options_.miscal) {
    // The obstacle sees the physical arm: the true positions, not the encoders'.
    touches = [m = *options_.miscal, touches = std::move(touches)](std::span<const double> clicks) {
      std::vector<double> truth(clicks.begin(), clicks.end());
      for (std::size_t i = 0; i < truth.size() && i < m.joints.size(); ++i)
        truth[i] = m.true_position(int(i + 1), truth[i]);
      return touches(truth);
    };
  }
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

double SimArm::true_position(int number) {
  const double clicks = joint(number).hardware().position_clicks();
  return options_.miscal ? options_.miscal->true_position(number, clicks) : clicks;
}

bool SimArm::move_by_hand_to(int number, double true_clicks) {
  SimJoint& j = joint(number);
  const double target = options_.miscal ? options_.miscal->device_position(number, true_clicks) : true_clicks;
  return j.turn_by_hand(target - j.hardware().position_clicks());
}

}  // namespace armctl::joint_sim

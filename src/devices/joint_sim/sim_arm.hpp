// The simulated SCARA arm: the joints of an ArmConfig (SimJoint = portable JointController
// + motor model) on one SimBus. The bus master talks to link(); tests and the real-time
// simulator (`armctl sim scara`) run it forward with run_until()/advance().
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "devices/joint_sim/arm_config.hpp"
#include "devices/joint_sim/contact_stop.hpp"
#include "devices/joint_sim/sim_bus.hpp"
#include "devices/joint_sim/sim_joint.hpp"

namespace armctl::joint_sim {

// How every joint of the simulated arm was "flashed" (joint_options.hpp): legacy-master
// mode (`sim?dialect=legacy`) and motor polarity.
struct SimArmOptions {
  joint_bus::JointOptions joints{};
};

class SimArm {
 public:
  explicit SimArm(ArmConfig config, SimArmOptions options = {});
  // The simulator section of config/scara.arm.json (default_arm_config_path()).
  static std::unique_ptr<SimArm> from_default_config();

  SimArm(const SimArm&) = delete;
  SimArm& operator=(const SimArm&) = delete;

  transport::JointBusLink& link() { return *bus_; }
  SimBus& bus() { return *bus_; }
  const ArmConfig& config() const { return config_; }
  const SimArmOptions& options() const { return options_; }

  TimePoint now() const { return bus_->now(); }
  void run_until(TimePoint t) { bus_->run_until(t); }
  void advance(Duration d) { bus_->advance(d); }

  int joint_count() const { return static_cast<int>(joints_.size()); }
  // Joint by number (1..7), brought up to now. Throws invalid_argument if absent.
  SimJoint& joint(int number);

  void set_fault_plan(FaultPlan plan) { bus_->set_fault_plan(std::move(plan)); }
  // Something the arm meets (the scene: `armctl sim scara --scene`; ContactStop): whether
  // the arm touches it with its joints at these positions (encoder clicks, one per joint
  // number - 1). Checked every millisecond of simulated time; a joint that moves the arm into
  // it stalls there.
  void set_obstacle(std::function<bool(std::span<const double>)> touches);

 private:
  ArmConfig config_;
  SimArmOptions options_;
  std::vector<std::unique_ptr<SimJoint>> joints_;  // index = number - 1 (null if absent)
  std::unique_ptr<SimBus> bus_;
  std::unique_ptr<ContactStop> contact_;
};

}  // namespace armctl::joint_sim

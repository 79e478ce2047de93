// The simulated SCARA arm: the joints of an ArmConfig (SimJoint = portable JointController
// + motor model) on one SimBus. The bus master talks to link(); tests and the real-time
// simulator (`armctl sim scara`) run it forward with run_until()/advance().
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/miscalibration.hpp"

#include "devices/joint_sim/arm_config.hpp"
#include "devices/joint_sim/contact_stop.hpp"
#include "devices/joint_sim/sim_bus.hpp"
#include "devices/joint_sim/sim_joint.hpp"

namespace armctl::joint_sim {

// How every joint of the simulated arm was "flashed" (joint_options.hpp): legacy-master
// mode (`sim?dialect=legacy`) and motor polarity.
struct SimArmOptions {
  joint_bus::JointOptions joints{};
  // Mis-assembled on purpose (`sim?miscal=SEED`, core/miscalibration.hpp): each joint was
  // homed away from where the arm file puts its zero, one turns the other way (motor and
  // encoder mounted reversed: the loop still closes, the arm moves the wrong way), and the
  // end stops stay where they are physically. Nothing on the bus shows it; only the physical
  // arm (true_position) does.
  std::optional<Miscalibration> miscal;
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
  // The clicks are the true positions (true_position): an obstacle stands in the physical world.
  void set_obstacle(std::function<bool(std::span<const double>)> touches);

  // What the simulator shows (the user's eyes), for tests that answer a calibration wizard as
  // a user would. The joint's true position: the clicks a well-built arm's joint (the one the
  // shipped arm file describes) would count at the pose this joint physically stands in; its
  // encoder's count without a miscalibration. Convert to SI with the shipped arm file's
  // joint_bus mapping (arm/sim_truth.hpp does, and gives the true tool position).
  double true_position(int number);
  // A hand turning the limp joint (loop off) until it stands at `true_clicks`. False (nothing
  // moves) while its position loop is on. Throws invalid_argument for an absent joint.
  bool move_by_hand_to(int number, double true_clicks);
  const std::optional<Miscalibration>& miscalibration() const { return options_.miscal; }

 private:
  ArmConfig config_;
  SimArmOptions options_;
  std::vector<std::unique_ptr<SimJoint>> joints_;  // index = number - 1 (null if absent)
  std::unique_ptr<SimBus> bus_;
  std::unique_ptr<ContactStop> contact_;
};

}  // namespace armctl::joint_sim

// The two arms the HIL tests run every case against: "sim" (the portable JointController
// compiled for the host, SimJoint) and "avr" (the firmware ELF on emulated ATmega328P
// chips, AvrJoint). Both put the same motor models on the same SimBus; the bus master
// talks to link() and cannot tell which one it has.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "devices/joint_avr/avr_arm.hpp"
#include "devices/joint_avr/eeprom_image.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "devices/joint_sim/sim_bus.hpp"
#include "devices/joint_sim/sim_joint.hpp"

namespace armctl::hil {

// Deliberate board faults, the same on both backends where the backend can have them.
struct Scenario {
  // Select line -> the joint number the board believes it has (a wrong EEPROM on "avr",
  // a controller begun with that number on "sim").
  std::map<int, std::uint8_t> believed_number;
  // Lines whose joint never answers (chip held in reset on "avr"; nothing on the line on
  // "sim").
  std::set<int> dead_lines;
  std::uint32_t baud = 0;  // 0: the config's
  // How every board was flashed (EEPROM settings byte on "avr", begin() options on "sim").
  joint_bus::JointOptions options{};
  // Lines whose motor leads are swapped (the motor model turns the other way).
  std::set<int> leads_swapped;
};

class ArmBackend {
 public:
  virtual ~ArmBackend() = default;
  virtual transport::JointBusLink& link() = 0;
  virtual joint_sim::SimBus& bus() = 0;
  // Physical state of the joint on a select line (brought up to now).
  virtual const joint_sim::JointHardware& hardware(int line) = 0;
  void advance(Duration d) { bus().advance(d); }
  TimePoint now() { return bus().now(); }
};

inline joint_sim::ArmConfig hil_arm_config(std::uint32_t baud, const std::set<int>& leads_swapped = {}) {
  joint_sim::ArmConfig config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  if (baud != 0) config.baud = baud;
  for (auto& j : config.joints) j.hardware.leads_swapped = leads_swapped.count(j.number) != 0;
  return config;
}

class SimBackend final : public ArmBackend {
 public:
  explicit SimBackend(const Scenario& s) : config_(hil_arm_config(s.baud, s.leads_swapped)) {
    std::vector<joint_sim::BusEndpoint*> endpoints(config_.joints.size(), nullptr);
    for (const auto& j : config_.joints) {
      if (s.dead_lines.count(j.number)) continue;
      std::uint8_t number = j.number;
      if (auto it = s.believed_number.find(j.number); it != s.believed_number.end()) number = it->second;
      joints_[j.number] = std::make_unique<joint_sim::SimJoint>(number, j.tuning, config_.baud, j.hardware,
                                                                TimePoint{}, s.options);
      endpoints[j.number - 1u] = joints_[j.number].get();
    }
    bus_ = std::make_unique<joint_sim::SimBus>(config_.baud, endpoints);
  }
  transport::JointBusLink& link() override { return *bus_; }
  joint_sim::SimBus& bus() override { return *bus_; }
  const joint_sim::JointHardware& hardware(int line) override {
    bus_->sync();
    return joints_.at(line)->hardware();
  }

 private:
  joint_sim::ArmConfig config_;
  std::map<int, std::unique_ptr<joint_sim::SimJoint>> joints_;
  std::unique_ptr<joint_sim::SimBus> bus_;
};

class AvrBackend final : public ArmBackend {
 public:
  explicit AvrBackend(const Scenario& s) {
    joint_sim::ArmConfig config = hil_arm_config(s.baud, s.leads_swapped);
    joint_avr::AvrArmOptions options;
    options.joints = s.options;
    for (const auto& [line, number] : s.believed_number) {
      options.eeprom_overrides[line] =
          joint_avr::joint_eeprom_image(number, config.baud, config.joint(line).tuning, s.options);
    }
    arm_ = std::make_unique<joint_avr::AvrArm>(std::move(config), options);
    for (int line : s.dead_lines) arm_->joint(line).set_held_in_reset(true);
  }
  transport::JointBusLink& link() override { return arm_->link(); }
  joint_sim::SimBus& bus() override { return arm_->bus(); }
  const joint_sim::JointHardware& hardware(int line) override { return arm_->joint(line).hardware(); }
  joint_avr::AvrArm& arm() { return *arm_; }

 private:
  std::unique_ptr<joint_avr::AvrArm> arm_;
};

inline std::unique_ptr<ArmBackend> make_backend(const std::string& name, const Scenario& s = {}) {
  if (name == "avr") return std::make_unique<AvrBackend>(s);
  return std::make_unique<SimBackend>(s);
}

}  // namespace armctl::hil

// The calibration wizard's engine against the mis-assembled simulators, on simulated time: an
// arm file of its own in a temporary directory, the simulator with `miscal`, and a "user"
// who answers from what the simulator shows (the physical arm's true positions) and moves
// joints by hand (move_by_hand_to with torque off).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include <fmt/core.h>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm/sim_truth.hpp"
#include "arm_files.hpp"
#include "calibration/rc_servo_bus.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::calibration::testing {

namespace fs = std::filesystem;

// The shipped files copied to a directory of the test's own (the wizard writes the arm file).
inline fs::path arm_dir(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() /
                       fmt::format("armctl-wizard-{}-{}-{}", tag,
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name(), ::getpid());
  fs::create_directories(dir);
  for (const char* f : {"xarm.arm.json", "xarm.urdf", "scara.arm.json", "scara.urdf"})
    fs::copy_file(arm::testing::config_path(f), dir / f, fs::copy_options::overwrite_existing);
  return dir;
}

// What both arms offer the scripted user: true device positions by ID, a hand.
class PhysicalArm {
 public:
  virtual ~PhysicalArm() = default;
  virtual std::vector<double> true_device() = 0;
  virtual bool hand(int id, double true_device) = 0;
  // Makes an Arm over the same device with another model (the calibrated one).
  virtual std::unique_ptr<arm::Arm> arm_with(const arm::ArmModel& model) = 0;
  virtual calibration::ServoBus* servos() { return nullptr; }
};

class XarmPhysical final : public PhysicalArm {
 public:
  explicit XarmPhysical(std::optional<Miscalibration> miscal) {
    xarm::XarmEmulatorOptions o;
    o.miscal = std::move(miscal);
    link = std::make_unique<robot_commands::testing::EmulatedLink>(9600, o);
    client = std::make_unique<robot_commands::Client>(*link);
    bus = std::make_unique<RcServoBus>(*client);
  }
  xarm::XarmServos& sim() { return link->emulator().servos(); }
  std::vector<double> true_device() override {
    std::vector<double> d;
    for (xarm::ServoId p = 1; p <= 6; ++p) d.push_back(sim().true_position(p));
    return d;
  }
  bool hand(int id, double units) override { return sim().move_by_hand_to(xarm::ServoId(id), units); }
  std::unique_ptr<arm::Arm> arm_with(const arm::ArmModel& model) override {
    return std::make_unique<arm::Arm>(model, std::make_unique<arm::RcArmDevice>(model, *client));
  }
  calibration::ServoBus* servos() override { return bus.get(); }

  std::unique_ptr<robot_commands::testing::EmulatedLink> link;
  std::unique_ptr<robot_commands::Client> client;
  std::unique_ptr<RcServoBus> bus;
};

class ScaraPhysical final : public PhysicalArm {
 public:
  explicit ScaraPhysical(std::optional<Miscalibration> miscal) {
    joint_sim::ArmConfig config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
    config.baud = 115200;
    joint_sim::SimArmOptions o;
    o.miscal = std::move(miscal);
    sim = std::make_unique<joint_sim::SimArm>(std::move(config), o);
    master = std::make_unique<joint_bus::BusMaster>(sim->link());
  }
  std::vector<double> true_device() override {
    std::vector<double> d;
    for (int j = 1; j <= 7; ++j) d.push_back(sim->true_position(j));
    return d;
  }
  bool hand(int id, double clicks) override { return sim->move_by_hand_to(id, clicks); }
  std::unique_ptr<arm::Arm> arm_with(const arm::ArmModel& model) override {
    return std::make_unique<arm::Arm>(model,
                                      std::make_unique<arm::BusArmDevice>(model, *master, sim->link(), "simulated SCARA"));
  }

  std::unique_ptr<joint_sim::SimArm> sim;
  std::unique_ptr<joint_bus::BusMaster> master;
};

}  // namespace armctl::calibration::testing

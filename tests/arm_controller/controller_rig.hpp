// Test rig: the SDK (robot_commands::Client) -> controller (Board + ArmController) ->
// simulated joint bus -> seven simulated joints, all in one thread on the simulated bus's
// clock. The link hands frames to the controller and, while the SDK waits for a reply,
// runs the controller (polling, scheduled drives, group playback) in simulated time.
#pragma once

#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "devices/arm_controller/controller_config.hpp"
#include "devices/arm_controller/controller_device.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::arm_controller::testing {

// The SDK's link to a device in this process (ControllerDevice, or CoreDevice:
// core_device_test.cpp): while the SDK waits for a reply the device runs in simulated time.
template <typename Device>
class DeviceRcLink final : public robot_commands::RcLink {
 public:
  void attach(Device& device) { device_ = &device; }
  void deliver(const rc::Frame& f) { inbox_.push_back(f); }
  void send(const rc::Frame& frame) override { device_->handle(frame); }
  std::optional<rc::Frame> receive(TimePoint deadline) override {
    while (inbox_.empty()) {
      if (device_->clock().now() >= deadline) return std::nullopt;
      device_->step(deadline);
    }
    rc::Frame f = inbox_.front();
    inbox_.pop_front();
    return f;
  }
  const Clock& clock() const override { return device_->clock(); }
  std::string describe() const override { return "in-process controller"; }

 private:
  Device* device_ = nullptr;
  std::deque<rc::Frame> inbox_;
};
using SimRcLink = DeviceRcLink<ControllerDevice>;

struct Rig {
  // leads_swapped: joints whose motor leads are the other way round (they run away).
  explicit Rig(std::optional<std::filesystem::path> state_dir = std::nullopt,
               std::uint32_t baud = 0, const std::vector<int>& leads_swapped = {}) {
    auto sim_config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
    if (baud != 0) sim_config.baud = baud;
    for (auto& j : sim_config.joints) {
      for (int n : leads_swapped) j.hardware.leads_swapped = j.hardware.leads_swapped || j.number == n;
    }
    arm = std::make_unique<joint_sim::SimArm>(std::move(sim_config));
    DeviceOptions o;
    o.state_dir = std::move(state_dir);
    o.log = [this](const std::string& line) { log.push_back(line); };
    device = std::make_unique<ControllerDevice>(
        arm->link(), joint_bus::MasterOptions{},
        load_controller_config(default_controller_config_path()), o,
        [this](const rc::Frame& f) { link.deliver(f); });
    link.attach(*device);
    robot_commands::ClientOptions co;
    co.servo_count = 7;
    co.reply_timeout = std::chrono::milliseconds(500);
    client = std::make_unique<robot_commands::Client>(link, co);
  }

  TimePoint now() const { return device->clock().now(); }
  void run_for(Duration d) { device->run_for(d); }
  // Actual joint position in clicks (the simulated encoder), not the controller's reading.
  int clicks(int joint) { return arm->joint(joint).controller().position(); }
  ArmController& controller() { return device->arm(); }
  bool logged(const std::string& needle) const {
    for (const auto& l : log)
      if (l.find(needle) != std::string::npos) return true;
    return false;
  }

  std::unique_ptr<joint_sim::SimArm> arm;
  SimRcLink link;
  std::unique_ptr<ControllerDevice> device;
  std::unique_ptr<robot_commands::Client> client;
  std::vector<std::string> log;
};

}  // namespace armctl::arm_controller::testing

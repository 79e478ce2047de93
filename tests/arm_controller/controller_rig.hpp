// Test rig: the SDK (robot_commands::Client) -> the arm controller (CoreDevice: the portable
// core on Linux) -> simulated joint bus -> seven simulated joints, all in one thread on the
// simulated bus's clock. While the SDK waits for a reply the controller runs (polling,
// queued commands, group playback) in simulated time.
#pragma once

#include <stdlib.h>

#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "devices/arm_controller/controller_config.hpp"
#include "devices/arm_controller/core_device.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::arm_controller::testing {

// A fresh directory for a state dir, removed at the end.
struct TempDir {
  TempDir() {
    char tmpl[] = "/tmp/armctl-controller-test-XXXXXX";
    path = ::mkdtemp(tmpl);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::filesystem::path path;
};

class SimRcLink final : public robot_commands::RcLink {
 public:
  void attach(CoreDevice& device) { device_ = &device; }
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
  CoreDevice* device_ = nullptr;
  std::deque<rc::Frame> inbox_;
};

struct Rig {
  // leads_swapped: joints whose motor leads are the other way round (they run away).
  explicit Rig(std::optional<std::filesystem::path> dir = std::nullopt, std::uint32_t baud = 0,
               const std::vector<int>& leads_swapped = {})
      : state_dir(std::move(dir)) {
    auto sim_config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
    if (baud != 0) sim_config.baud = baud;
    for (auto& j : sim_config.joints)
      for (int n : leads_swapped) j.hardware.leads_swapped = j.hardware.leads_swapped || j.number == n;
    arm = std::make_unique<joint_sim::SimArm>(std::move(sim_config));
    start();
  }
  // The controller process started (again) over the same arm and state dir.
  void start() {
    client.reset();
    device.reset();
    CoreDeviceOptions o;
    o.state_dir = state_dir;
    o.log = [this](const std::string& line) { log.push_back(line); };
    o.link_losses = [this] { return losses; };
    device = std::make_unique<CoreDevice>(arm->link(), config, o, [this](const rc::Frame& f) { link.deliver(f); });
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
  // Clicks a Robot Commands position maps to for this joint (no offset).
  int target(int joint, int position) const { return config.joint(joint)->map.to_clicks(position); }
  const controller::JointState& state(int joint) const { return device->joint_state(joint); }
  bool logged(const std::string& needle) const {
    for (const auto& l : log)
      if (l.find(needle) != std::string::npos) return true;
    return false;
  }
  // Reads group notifications until one of `kind` (true) or none for `within`.
  bool wait_for(robot_commands::GroupEventKind kind, Duration within) {
    while (auto e = client->wait_event(now() + within))
      if (e->kind == kind) return true;
    return false;
  }

  std::optional<std::filesystem::path> state_dir;
  ControllerConfig config = load_controller_config(default_controller_config_path());
  std::unique_ptr<joint_sim::SimArm> arm;
  SimRcLink link;
  std::unique_ptr<CoreDevice> device;
  std::unique_ptr<robot_commands::Client> client;
  std::vector<std::string> log;
  std::uint64_t losses = 0;
};

}  // namespace armctl::arm_controller::testing

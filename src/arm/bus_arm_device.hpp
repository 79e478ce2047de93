// An arm on the joint bus directly (the SCARA through BusMaster): clicks per joint, moves
// planned so that every joint arrives at the same instant (the arm controller's planner,
// sync_plan), stop and torque by the joint-bus commands.
#pragma once

#include <vector>

#include "arm/arm_device.hpp"
#include "devices/joint_bus/sync_plan.hpp"
#include "devices/joint_bus/bus_master.hpp"

namespace armctl::arm {

class BusArmDevice final : public ArmDevice {
 public:
  // `master` and `link` (the master's link) must outlive the device.
  BusArmDevice(const ArmModel& model, joint_bus::BusMaster& master, transport::JointBusLink& link,
               std::string description);

  Protocol protocol() const override { return Protocol::joint_bus; }
  std::string description() const override { return description_; }
  const Clock& clock() const override { return link_.clock(); }
  // One sweep of position reads (7 transactions: 58 ms at 9600) is already a poll.
  Duration poll_interval() const override { return std::chrono::milliseconds(20); }
  Result<std::vector<double>> read_positions() override;
  // One get_position: a servo loop's read-back one joint per cycle.
  std::optional<Duration> joint_read_time() const override { return transaction_; }
  Result<double> read_joint(int joint) override;
  Status move(const std::vector<std::optional<double>>& targets, Duration duration) override;
  // set_speed 0 to every joint, back to back: each brakes at its own deceleration and holds.
  Status stop() override;
  Status set_torque(bool on) override;  // set_pid_state
  Status release(int joint) override;   // set_pid_state of that joint
  // A stream point is one drive_to per joint (and a set_speed where the speed changes): the
  // joint's setpoint ramp follows the moving target at the speed the point asks for.
  Duration stream_period(bool with_read) const override;
  Duration stream_latency() const override { return transaction_; }
  Status stream(const std::vector<double>& targets, const std::vector<double>& velocities, Duration in) override;
  Status idle(Duration d) override;
  DeviceHealth health() override;  // the joints' fault flags (firmware without diagnostics: none)
  Status clear_faults() override;

 private:
  Status failed(const Error& e) const;

  joint_bus::BusMaster& master_;
  transport::JointBusLink& link_;
  std::string description_;
  std::vector<int> numbers_;  // joint-bus number per model joint
  std::vector<joint_bus::JointProfile> profiles_;
  Duration transaction_;  // one set_speed or drive_to on this bus
  std::vector<int> streamed_percent_;  // set_speed last sent while streaming (-1: not yet)
  std::vector<std::optional<long>> streamed_target_;  // drive_to last sent while streaming
};

}  // namespace armctl::arm

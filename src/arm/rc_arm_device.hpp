// An arm on any Robot Commands board: the xArm, the emulated xArm, or armctl's arm
// controller (the SCARA arm through Robot Commands). Servo IDs come from the arm model.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "arm/arm_device.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::arm {

class RcArmDevice final : public ArmDevice {
 public:
  // `client` must outlive the device.
  RcArmDevice(const ArmModel& model, robot_commands::Client& client);

  Protocol protocol() const override { return Protocol::robot_commands; }
  std::string description() const override;
  const Clock& clock() const override { return client_.clock(); }
  Duration poll_interval() const override { return client_.options().poll_interval; }
  // In the commanded frame: each servo's read-back less the offset it holds (read once,
  // then known to the client: the first read costs one ServoOffsetRead more). After
  // request_read: that request's reply.
  Result<std::vector<double>> read_positions() override;
  // A ServoPositionRead's request (5 + n bytes) sent now, its reply collected by the next
  // read_positions (client.hpp request_positions).
  std::optional<Duration> read_request_time() const override;
  Status request_read() override;
  // The board moves every servo linearly over the time (0..30 s); positions round to whole
  // servo units.
  Status move(const std::vector<std::optional<double>>& targets, Duration duration) override;
  // Stops any action group, then holds every servo where it reads now.
  Status stop() override;
  Status set_torque(bool on) override;
  Status release(int joint) override;
  // A stream point is one MultiServoMove of every servo (7 + 3 n bytes: 25 for six, 26 ms at
  // 9600 baud), timed to arrive when the point is due; a read adds its request and reply.
  Duration stream_period(bool with_read) const override;
  Duration stream_latency() const override;
  Status stream(const std::vector<double>& targets, const std::vector<double>& velocities, Duration in) override;
  Status idle(Duration d) override;
  ActionGroups* action_groups() override { return &groups_; }
  // The battery; on a board with armctl's JointFaultRead extension (the Mega arm
  // controller) also each servo's faults. A board without it (an xArm) costs one
  // extension_timeout on the first call, none after.
  DeviceHealth health() override;
  Status clear_faults() override;

 private:
  Status hold_where_they_stand();  // a move to where every servo reads now, in no time
  // Each servo's read-back less the offset it holds (`offsets` per joint).
  Result<std::vector<double>> commanded_frame(const std::vector<rc::ServoPosition>& read,
                                              const std::vector<int>& offsets) const;

  robot_commands::Client& client_;
  RcActionGroups groups_{client_};
  std::vector<std::uint8_t> servos_;  // per joint, in the model's order
};

// One line of DeviceHealth::faults for a JointFaultRead report ("servo 3: runaway (bridge
// off until clear-faults)"); nothing for a servo that answers, follows and holds no fault.
std::optional<std::string> describe_joint_faults(const rc::JointFaultReport& report);

}  // namespace armctl::arm

// An optional capability of an arm device (ArmDevice::action_groups()): sequences of servo
// positions stored on the device and replayed by it alone (a Robot Commands board: the xArm,
// or armctl's arm controller; docs/action-groups.md). Apps reach action groups only through
// this, never through the board's client, so any device that stores groups can offer them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "devices/robot_commands/client.hpp"
#include "devices/robot_commands/group_event.hpp"

namespace armctl::arm {

class ActionGroups {
 public:
  virtual ~ActionGroups() = default;
  // Stores `actions` as `group` (0..254); every action is validated before the first is sent.
  virtual Status download(std::uint8_t group, const std::vector<robot_commands::GroupAction>& actions) = 0;
  // Runs `group` `times` times (0: until stopped); returns once asked.
  virtual Status run(std::uint8_t group, std::uint16_t times) = 0;
  // The same, and waits until the device says it started (robot_commands::GroupNotStarted
  // when it does not: the group is empty or missing).
  virtual Status run_started(std::uint8_t group, std::uint16_t times) = 0;
  virtual Status stop() = 0;
  virtual Status erase(std::uint8_t group) = 0;                             // 255: every group
  virtual Status set_speed(std::uint8_t group, std::uint16_t percent) = 0;  // 255: every group
  // Notifications (started, stopped, finished): received until `deadline` on the device's
  // clock, then taken oldest first.
  virtual Result<std::size_t> pump_events(TimePoint deadline) = 0;
  virtual std::optional<robot_commands::GroupEvent> next_event() = 0;
  virtual const Clock& clock() const = 0;
};

// Action groups on a Robot Commands board, through its client (which must outlive it).
class RcActionGroups final : public ActionGroups {
 public:
  explicit RcActionGroups(robot_commands::Client& client) : client_(client) {}
  Status download(std::uint8_t group, const std::vector<robot_commands::GroupAction>& actions) override {
    return client_.download_group(group, actions);
  }
  Status run(std::uint8_t group, std::uint16_t times) override { return client_.run_group(group, times); }
  Status run_started(std::uint8_t group, std::uint16_t times) override;
  Status stop() override { return client_.stop_group(); }
  Status erase(std::uint8_t group) override { return client_.erase_group(group); }
  Status set_speed(std::uint8_t group, std::uint16_t percent) override { return client_.set_group_speed(group, percent); }
  Result<std::size_t> pump_events(TimePoint deadline) override { return client_.pump_events(deadline); }
  std::optional<robot_commands::GroupEvent> next_event() override { return client_.next_event(); }
  const Clock& clock() const override { return client_.clock(); }

 private:
  robot_commands::Client& client_;
};

}  // namespace armctl::arm

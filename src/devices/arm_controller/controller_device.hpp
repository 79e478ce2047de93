// The whole arm controller minus its upstream wire: the generic Robot Commands board side
// (rc_board::Board, with action groups in a GroupStore) over the ArmController backend.
// Single-threaded and clock-driven: on a simulated bus (SimClock) tests call run_until() and
// everything — polling, scheduled drive commands, group playback — happens at exact
// simulated instants. ControllerRunner adds the upstream pty/serial port.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "devices/arm_controller/arm_controller.hpp"
#include "devices/arm_controller/served_controller.hpp"
#include "devices/rc_board/board.hpp"
#include "devices/rc_board/group_store.hpp"

namespace armctl::arm_controller {

struct DeviceOptions {
  // Action groups (group-NNN.grp) and controller-settings.json; nothing = in memory only.
  std::optional<std::filesystem::path> state_dir;
  std::function<std::uint16_t()> supply_millivolts;
  std::function<void(const std::string&)> log;
  // How many times the bus link has been lost so far (ReconnectingLink::losses); empty for a
  // link that cannot be lost. On each new loss pending commands and group playback end, so
  // that nothing moves when the link comes back until a new command arrives.
  std::function<std::uint64_t()> link_losses;
};

class ControllerDevice final : public ServedController {
 public:
  // Throws ArmctlError (config/bus mismatch, unusable state dir). Calls arm().start().
  ControllerDevice(transport::JointBusLink& link, joint_bus::MasterOptions master_options,
                   ControllerConfig config, DeviceOptions options, rc_board::Board::Output output);

  ArmController& arm() { return *arm_; }
  const ArmController& arm() const { return *arm_; }
  rc_board::Board& board() { return *board_; }
  rc_board::GroupStore& groups() { return *groups_; }
  const Clock& clock() const override { return arm_->clock(); }

  void receive(std::span<const std::uint8_t> bytes) override { board_->receive(bytes); }
  void handle(const rc::Frame& frame) { board_->handle(frame); }

  // One bus step (see ArmController::service) with group playback kept on time;
  // `limit` bounds any waiting.
  void step(TimePoint limit) override;
  // Steps until the bus clock reaches `t` (a last poll may end a little after it).
  void run_until(TimePoint t);
  void run_for(Duration d) { run_until(clock().now() + d); }

 private:
  std::unique_ptr<ArmController> arm_;
  std::unique_ptr<rc_board::GroupStore> groups_;
  std::unique_ptr<rc_board::Board> board_;
  std::function<std::uint64_t()> link_losses_;
  std::uint64_t losses_seen_ = 0;
};

}  // namespace armctl::arm_controller

#include "devices/arm_controller/controller_device.hpp"

namespace armctl::arm_controller {

ControllerDevice::ControllerDevice(transport::JointBusLink& link, joint_bus::MasterOptions master_options,
                                   ControllerConfig config, DeviceOptions options,
                                   rc_board::Board::Output output) {
  ControllerOptions co;
  co.state_dir = options.state_dir;
  co.supply_millivolts = options.supply_millivolts;
  co.log = options.log;
  arm_ = std::make_unique<ArmController>(link, master_options, std::move(config), std::move(co));
  groups_ = options.state_dir
                ? std::make_unique<rc_board::GroupStore>(*options.state_dir)
                : std::make_unique<rc_board::GroupStore>(rc_board::GroupStore::in_memory());
  if (options.log)
    for (const auto& p : groups_->problems()) options.log("state dir: " + p);
  board_ = std::make_unique<rc_board::Board>(*arm_, *groups_, arm_->clock(), std::move(output));
  if (options.log) board_->set_log(options.log);
  link_losses_ = options.link_losses;
  arm_->start();
}

void ControllerDevice::step(TimePoint limit) {
  board_->poll();
  if (auto wake = board_->next_wakeup()) limit = std::min(limit, *wake);
  arm_->service(limit);
  // Checked between bus steps, never inside one: the loss is seen here, after the
  // transaction that met it has failed like one to a dead joint.
  if (link_losses_ && link_losses_() != losses_seen_) {
    losses_seen_ = link_losses_();
    board_->stop_playback("joint bus link lost");
    arm_->link_lost();
  }
  board_->poll();
}

void ControllerDevice::run_until(TimePoint t) {
  while (clock().now() < t) step(t);
}

}  // namespace armctl::arm_controller

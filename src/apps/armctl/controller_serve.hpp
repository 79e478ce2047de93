// Serving the arm controller to a host (shared by `armctl controller` and
// `armctl sim scara --robot-commands`): opens the upstream, prints the path a host opens,
// serves until SIGINT/SIGTERM, prints what happened.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "devices/arm_controller/controller_config.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::cli {

struct ControllerServeArgs {
  std::string upstream = "pty";
  std::string link;       // optional symlink to the pty
  std::string state_dir;  // empty: in memory
  std::string label = "controller";
  // A bus link that can be lost and comes back (ReconnectingLink::losses); empty otherwise.
  std::function<std::uint64_t()> link_losses;
  bool json = false;  // --json: the log as JSON lines on stdout (apps/armctl/server_log.hpp)
};

// The controller's config from the arm `--arm` names (scara, xarm or an arm file, as in every
// command; empty: scara): its "arm_controller" section. A controller config of the old form
// (config/scara-arm.json) is still read, with a warning.
arm_controller::ControllerConfig controller_config_for(const std::string& arm);

// `link` may be a simulated bus: it is then paced to the wall clock. Joints of the legacy
// dialect (master_options.dialect) are refused: the controller speaks the standard one.
void serve_controller(transport::JointBusLink& link, joint_bus::MasterOptions master_options,
                      arm_controller::ControllerConfig config, const ControllerServeArgs& args,
                      std::function<std::uint16_t()> supply_millivolts = {});

}  // namespace armctl::cli

#include "apps/armctl/controller_serve.hpp"
#include "apps/armctl/serve_support.hpp"
#include "apps/armctl/server_log.hpp"

#include <cstdio>
#include <memory>
#include <optional>

#include <fmt/core.h>

#include "arm/arm_model.hpp"
#include "core/error.hpp"
#include "devices/arm_controller/controller_runner.hpp"
#include "transport/paced_link.hpp"

namespace armctl::cli {

arm_controller::ControllerConfig controller_config_for(const std::string& arm) {
  return arm_controller::load_controller_config(arm::arm_file_path(arm.empty() ? "scara" : arm));
}

void serve_controller(transport::JointBusLink& bus, joint_bus::MasterOptions master_options,
                      arm_controller::ControllerConfig config, const ControllerServeArgs& args,
                      std::function<std::uint16_t()> supply_millivolts) {
  namespace ac = arm_controller;
  const ac::Upstream upstream = ac::parse_upstream(args.upstream);
  if (!args.link.empty() && !upstream.pty)
    throw ArmctlError(ErrorKind::invalid_argument, "--link is only for --upstream pty");

  std::optional<transport::PacedLink> paced;
  transport::JointBusLink* link = &bus;
  if (transport::runs_on_simulated_time(bus)) link = &paced.emplace(bus);

  ac::ControllerRunner runner(upstream);
  ac::DeviceOptions options;
  if (!args.state_dir.empty()) options.state_dir = args.state_dir;
  options.supply_millivolts = std::move(supply_millivolts);
  options.link_losses = args.link_losses;
  const ServerLog log(args.label, args.json);
  options.log = [&log](const std::string& m) { log.line(m); };
  const std::size_t joints = config.joints.size();
  ac::ControllerDevice device(*link, master_options, std::move(config), options, runner.make_output());

  const PtySymlink symlink(args.link, runner.host_path());
  const StopOnSignals stop_on_signals(runner);

  log.started({{"joints", joints}, {"link", args.link}, {"joint_bus_baud", link->baud()}},
              fmt::format("{}: Robot Commands on {}{} (servos 1..{} = joints), joint bus at {} baud; Ctrl-C to stop",
                          args.label, runner.host_path(), args.link.empty() ? "" : " linked from " + args.link,
                          joints, link->baud()),
              runner.host_path());
  for (int j : device.arm().servos()) {
    const auto& s = device.arm().joint_status(j);
    log.line(fmt::format("joint {} {}: {}", j, device.arm().config().joint(j)->name,
                         s.answering ? fmt::format("at {} clicks", s.clicks.value_or(0)) : "NOT ANSWERING: " + s.last_fault));
  }

  runner.run(device);

  const auto b = device.board().stats();
  const auto& c = device.arm().stats();
  log.stopped({{"frames", b.frames}, {"handled", b.handled}, {"ignored", b.ignored()}, {"moves", c.moves},
               {"refused_moves", c.refused_moves}, {"polls", c.polls}, {"sweeps", c.sweeps},
               {"poll_failures", c.poll_failures}, {"command_failures", c.command_failures},
               {"following_lost", c.following_lost}, {"runaway_faults", c.runaway_faults},
               {"following_error_faults", c.following_error_faults}},
              fmt::format("{}: stopped; {} frames ({} handled, {} ignored); {} moves ({} refused: joint not answering); "
                          "{} polls in {} sweeps, {} poll failures, {} command failures; {} times a joint stopped "
                          "following ({} runaway, {} following-error faults reported)",
                          args.label, b.frames, b.handled, b.ignored(), c.moves, c.refused_moves, c.polls, c.sweeps,
                          c.poll_failures, c.command_failures, c.following_lost, c.runaway_faults,
                          c.following_error_faults));
  for (int j : device.arm().servos()) {
    const auto& s = device.arm().joint_status(j);
    if (s.joint_faults != 0) log.line(fmt::format("joint {} {}: {}", j, device.arm().config().joint(j)->name, s.diagnostics));
  }
}

}  // namespace armctl::cli

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
#include "devices/arm_controller/core_device.hpp"
#include "devices/joint_bus/joint_diagnostics.hpp"
#include "transport/paced_link.hpp"

namespace armctl::cli {

arm_controller::ControllerConfig controller_config_for(const std::string& arm) {
  return arm_controller::load_controller_config(arm::arm_file_path(arm.empty() ? "scara" : arm));
}

void serve_controller(transport::JointBusLink& bus, joint_bus::MasterOptions master_options,
                      arm_controller::ControllerConfig config, const ControllerServeArgs& args,
                      std::function<std::uint16_t()> supply_millivolts) {
  namespace ac = arm_controller;
  if (master_options.dialect != joint_bus::Dialect::standard)
    throw ArmctlError(ErrorKind::unsupported,
                      "the arm controller speaks the joint bus's standard dialect; joints in legacy-master mode "
                      "answer in the other one: flash them with armctl's joint firmware in standard mode "
                      "(docs/firmware.md, \"Migrating from the original boards\")");
  const ac::Upstream upstream = ac::parse_upstream(args.upstream);
  if (!args.link.empty() && !upstream.pty)
    throw ArmctlError(ErrorKind::invalid_argument, "--link is only for --upstream pty");

  std::optional<transport::PacedLink> paced;
  transport::JointBusLink* link = &bus;
  if (transport::runs_on_simulated_time(bus)) link = &paced.emplace(bus);

  ac::ControllerRunner runner(upstream);
  const ServerLog log(args.label, args.json);
  ac::CoreDeviceOptions options;
  if (!args.state_dir.empty()) options.state_dir = args.state_dir;
  options.supply_millivolts = std::move(supply_millivolts);
  options.link_losses = args.link_losses;
  options.log = [&log](const std::string& m) { log.line(m); };
  const std::size_t joints = config.joints.size();
  ac::CoreDevice device(*link, std::move(config), options, runner.make_output());

  const PtySymlink symlink(args.link, runner.host_path());
  const StopOnSignals stop_on_signals(runner);
  log.started({{"joints", joints}, {"link", args.link}, {"joint_bus_baud", link->baud()}},
              fmt::format("{}: Robot Commands on {}{} (servos 1..{} = joints), joint bus at {} baud; Ctrl-C to stop",
                          args.label, runner.host_path(), args.link.empty() ? "" : " linked from " + args.link,
                          joints, link->baud()),
              runner.host_path());
  for (const auto& j : device.config().joints) {
    const auto& s = device.joint_state(j.number);
    log.line(fmt::format("joint {} {}: {}", j.number, j.name,
                         s.answering ? fmt::format("at {} clicks", s.clicks)
                                     : fmt::format("NOT ANSWERING (status {})", s.last_fault)));
  }

  runner.run(device);

  const auto& c = device.core().stats();
  log.stopped({{"frames", c.frames}, {"ignored", c.ignored_frames}, {"torn_frames", device.torn_frames()},
               {"moves", c.moves}, {"refused_moves", c.refused_moves}, {"polls", c.polls}, {"sweeps", c.sweeps},
               {"poll_failures", c.poll_failures}, {"command_failures", c.command_failures},
               {"following_lost", c.following_lost}, {"stalls", c.stalls}, {"runaway_faults", c.runaway_faults},
               {"following_error_faults", c.following_error_faults}},
              fmt::format("{}: stopped; {} frames ({} ignored, {} torn); {} moves ({} refused: joint not answering); "
                          "{} polls in {} sweeps, {} poll failures, {} command failures; {} times a joint stopped "
                          "following, {} stalls ({} runaway, {} following-error faults reported)",
                          args.label, c.frames, c.ignored_frames, device.torn_frames(), c.moves, c.refused_moves,
                          c.polls, c.sweeps, c.poll_failures, c.command_failures, c.following_lost, c.stalls,
                          c.runaway_faults, c.following_error_faults));
  for (const auto& j : device.config().joints) {
    const auto& s = device.joint_state(j.number);
    if (s.diagnostics_read && s.diagnostics[0] != 0)
      log.line(fmt::format("joint {} {}: faults held: {}", j.number, j.name, joint_bus::describe_faults(s.diagnostics[0])));
  }
}

}  // namespace armctl::cli

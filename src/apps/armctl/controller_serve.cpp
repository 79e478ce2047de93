#include "apps/armctl/controller_serve.hpp"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/core.h>

#include "core/error.hpp"
#include "devices/arm_controller/controller_runner.hpp"
#include "devices/arm_controller/paced_link.hpp"

namespace armctl::cli {

namespace {

arm_controller::ControllerRunner* g_controller_runner = nullptr;  // for the signal handler

extern "C" void on_controller_stop_signal(int) {
  if (g_controller_runner) g_controller_runner->request_stop();  // sets an atomic flag
}

}  // namespace

void serve_controller(transport::JointBusLink& bus, joint_bus::MasterOptions master_options,
                      arm_controller::ControllerConfig config, const ControllerServeArgs& args,
                      std::function<std::uint16_t()> supply_millivolts) {
  namespace ac = arm_controller;
  const ac::Upstream upstream = ac::parse_upstream(args.upstream);
  if (!args.link.empty() && !upstream.pty)
    throw ArmctlError(ErrorKind::invalid_argument, "--link is only for --upstream pty");

  std::optional<ac::PacedLink> paced;
  transport::JointBusLink* link = &bus;
  if (ac::runs_on_simulated_time(bus)) link = &paced.emplace(bus);

  ac::ControllerRunner runner(upstream);
  ac::DeviceOptions options;
  if (!args.state_dir.empty()) options.state_dir = args.state_dir;
  options.supply_millivolts = std::move(supply_millivolts);
  const std::string label = args.label;
  options.log = [label](const std::string& m) {
    fmt::print(stderr, "{}: {}\n", label, m);
    std::fflush(stderr);
  };
  const std::size_t joints = config.joints.size();
  ac::ControllerDevice device(*link, master_options, std::move(config), options, runner.make_output());

  namespace fs = std::filesystem;
  if (!args.link.empty()) {
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(args.link, ec))) fs::remove(args.link, ec);
    fs::create_symlink(runner.host_path(), args.link, ec);
    if (ec)
      throw ArmctlError(ErrorKind::io, fmt::format("cannot create link {} -> {}: {}", args.link,
                                                   runner.host_path(), ec.message()));
  }
  g_controller_runner = &runner;
  struct sigaction action {};
  action.sa_handler = on_controller_stop_signal;
  sigemptyset(&action.sa_mask);
  struct sigaction old_int {}, old_term {};
  sigaction(SIGINT, &action, &old_int);
  sigaction(SIGTERM, &action, &old_term);

  fmt::print("{}\n", runner.host_path());
  fmt::print(stderr, "{}: Robot Commands on {}{} (servos 1..{} = joints), joint bus at {} baud; Ctrl-C to stop\n",
             label, runner.host_path(), args.link.empty() ? "" : " linked from " + args.link, joints,
             link->baud());
  for (int j : device.arm().servos()) {
    const auto& s = device.arm().joint_status(j);
    fmt::print(stderr, "{}: joint {} {}: {}\n", label, j, device.arm().config().joint(j)->name,
               s.answering ? fmt::format("at {} clicks", s.clicks.value_or(0)) : "NOT ANSWERING: " + s.last_fault);
  }
  std::fflush(stdout);
  std::fflush(stderr);

  runner.run(device);

  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  g_controller_runner = nullptr;
  if (!args.link.empty()) {
    std::error_code ec;
    fs::remove(args.link, ec);
  }
  const auto b = device.board().stats();
  const auto& c = device.arm().stats();
  fmt::print(stderr,
             "{}: stopped; {} frames ({} handled, {} ignored); {} moves ({} refused: joint not answering); "
             "{} polls in {} sweeps, {} poll failures, {} command failures\n",
             label, b.frames, b.handled, b.ignored(), c.moves, c.refused_moves, c.polls, c.sweeps,
             c.poll_failures, c.command_failures);
}

}  // namespace armctl::cli

// armctl sim scara [--listen PATH] [--baud N] [--arm ARM] (and sim xarm: sim_xarm_command.cpp)
// Runs the simulated SCARA arm as a long-lived process, paced to the wall clock, serving its
// joint bus on a unix socket so that `armctl bus --device unix:PATH ...` keeps the arm's
// state between invocations. SIGINT/SIGTERM stop it cleanly (socket file removed).
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/controller_serve.hpp"
#include "apps/armctl/number_options.hpp"
#include "apps/armctl/serve_support.hpp"
#include "arm/arm_model.hpp"
#include "core/arm_file_sections.hpp"
#include "core/debug_log.hpp"
#include "core/error.hpp"
#include "core/miscalibration.hpp"
#include "apps/armctl/server_log.hpp"
#include "apps/armctl/sim_scene.hpp"
#include "devices/joint_bus/sim_link_server.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "transport/serial_port.hpp"

namespace armctl::cli {

namespace {

struct SimArgs {
  std::string listen = "/tmp/armctl-scara.sock";
  std::uint32_t baud = 0;  // 0: the config's
  std::string config;  // the old --config: a simulator config file (now the arm file's section)
  // --robot-commands: the whole arm as a Robot Commands device on a pty (SimArm + arm
  // controller in this process) instead of the joint bus on a unix socket.
  bool robot_commands = false;
  std::string arm;  // scara or an arm file (default scara): its simulator and arm_controller sections
  ControllerServeArgs serve{"pty", "", "", "sim scara", {}, false};
  // --controller mega: the Mega controller firmware and the joint firmware on emulated
  // chips, in the test tool armctl-mega-sim (libsimavr is GPL: armctl never links it).
  std::string controller;
  std::string scene;  // --scene: what the arm meets
  std::string miscal;  // --miscal SEED: mis-assembled on purpose (core/miscalibration.hpp)
};

// Replaces this process with armctl-mega-sim from armctl's own directory (build trees with
// ARMCTL_HIL only); returns only by throwing.
[[noreturn]] void exec_mega_sim(const SimArgs& args) {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const auto tool = (ec ? std::filesystem::path(".") : self.parent_path()) / "armctl-mega-sim";
  if (!std::filesystem::exists(tool))
    throw ArmctlError(ErrorKind::unsupported,
                      fmt::format("--controller mega needs {} (a test tool built with -DARMCTL_HIL=ON, "
                                  "never installed: docs/mega-controller.md)", tool.string()));
  std::vector<std::string> words{tool.string()};
  if (args.baud != 0) words.insert(words.end(), {"--baud", std::to_string(args.baud)});
  if (!args.serve.link.empty()) words.insert(words.end(), {"--link", args.serve.link});
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  ::execv(tool.c_str(), argv.data());
  throw ArmctlError(ErrorKind::io, fmt::format("cannot start {}: {}", tool.string(), std::strerror(errno)));
}

void run_sim_scara(const SimArgs& args) {
  if (!args.controller.empty()) {
    if (args.controller != "mega")
      throw ArmctlError(ErrorKind::invalid_argument,
                        fmt::format("--controller {}: allowed is mega (the Mega controller firmware on emulated "
                                    "silicon); without --controller, --robot-commands runs the Linux one",
                                    args.controller));
    if (args.robot_commands || !args.arm.empty() || !args.serve.state_dir.empty() || !args.config.empty() ||
        args.serve.json || !args.scene.empty() || !args.miscal.empty())
      throw ArmctlError(ErrorKind::invalid_argument,
                        "--controller mega takes only --baud and --link (the firmware has the arm built in)");
    exec_mega_sim(args);
  }
  if (!args.robot_commands && (!args.serve.link.empty() || !args.serve.state_dir.empty()))
    throw ArmctlError(ErrorKind::invalid_argument,
                      "--link and --state-dir belong to --robot-commands (the arm controller's pty); without it "
                      "the simulated arm serves the joint bus on --listen");
  // One arm file for the simulator and the controller (--arm, as in every command). The old
  // options still work, with a warning: --config named the simulator's config, and --arm the
  // controller's (config/scara.json, config/scara-arm.json: now the arm file's sections).
  std::filesystem::path sim_file = arm::arm_file_path(args.arm.empty() ? "scara" : args.arm);
  std::string controller_arm = args.arm;
  if (!args.arm.empty() && !arm_file::is_arm_file(sim_file)) {
    arm_file::warn_once(fmt::format("sim scara --arm {}: a controller config of the old form; --arm now takes "
                                    "an arm file (config/scara.arm.json) for the simulator and the controller",
                                    args.arm));
    sim_file = arm::arm_file_path("scara");
  }
  if (!args.config.empty()) {
    arm_file::warn_once(fmt::format("sim scara --config {}: --config is now --arm, an arm file "
                                    "(config/scara.arm.json) whose \"simulator\" section the simulator reads",
                                    args.config));
    sim_file = args.config;
  }
  joint_sim::ArmConfig config = joint_sim::load_arm_config(sim_file);
  if (args.baud != 0) config.baud = args.baud;
  joint_sim::SimArmOptions sim_options;
  if (!args.miscal.empty()) {
    // The truth stays out of normal output: the wizard is there to find it.
    sim_options.miscal = make_miscalibration(MiscalArm::scara, parse_miscal_seed("--miscal", args.miscal).value());
    debug_log("sim scara: " + describe(*sim_options.miscal));
  }
  joint_sim::SimArm arm(std::move(config), std::move(sim_options));
  if (!args.scene.empty())
    arm.set_obstacle(sim_obstacle(args.arm.empty() || !arm_file::is_arm_file(arm::arm_file_path(args.arm)) ? "scara" : args.arm,
                                  arm::Protocol::joint_bus, args.scene));
  if (args.robot_commands) {
    auto controller_config = controller_config_for(controller_arm);
    const auto supply_mv = static_cast<std::uint16_t>(arm.config().joints.front().hardware.motor.supply_v * 1000.0);
    serve_controller(arm.link(), {}, std::move(controller_config), args.serve, [supply_mv] { return supply_mv; });
    return;
  }
  joint_bus::SimLinkServer server(arm.link(), args.listen);
  server.set_tick([&arm] { arm.bus().sync(); });
  const ServerLog log("sim scara", args.serve.json, stdout);
  server.set_log([&log](const std::string& line) { log.line(line); });

  const StopOnSignals stop_on_signals(server);

  log.started({{"joints", arm.joint_count()}, {"baud", arm.config().baud}, {"listen", args.listen},
               {"scene", args.scene}},
              fmt::format("sim scara: {} joints at {} baud, listening on {}{} (Ctrl-C to stop)", arm.joint_count(),
                          arm.config().baud, args.listen,
                          args.scene.empty() ? "" : ", stopping at contact with " + args.scene));
  server.run();
  log.stopped({{"masters_served", server.stats().clients}, {"bytes_to_masters", server.stats().bytes_to_master}},
              fmt::format("sim scara: stopped ({} masters served, {} bytes to masters)", server.stats().clients,
                          server.stats().bytes_to_master));
}

}  // namespace

void add_sim_command(CLI::App& app) {
  auto args = std::make_shared<SimArgs>();
  CLI::App* sim = app.add_subcommand("sim", "Long-lived simulated arms: the SCARA arm, the emulated xArm board");
  sim->require_subcommand(1);
  add_sim_xarm_command(*sim);
  CLI::App* scara = sim->add_subcommand("scara", "The simulated SCARA arm (7 joints on a joint bus) on a unix socket");
  scara->add_option("--listen", args->listen, "Unix socket path (default /tmp/armctl-scara.sock)");
  scara->add_option("--baud", args->baud, "Joint bus baud (default: the config's, 9600)")
      ->check(standard_baud());
  scara->add_option("--arm", args->arm,
                    "scara | an arm file: its simulator and arm_controller sections (default scara, "
                    "config/scara.arm.json)");
  scara->add_option("--config", args->config, "Old form of --arm (a simulator config file); still read, with a warning");
  scara->add_flag("--robot-commands", args->robot_commands,
                  "Serve the whole arm as a Robot Commands device on a pty (arm controller inside; prints the pty path)");
  scara->add_option("--link", args->serve.link,
                    "With --robot-commands or --controller: also create this symlink to the pty");
  scara->add_option("--state-dir", args->serve.state_dir, "With --robot-commands: keep groups, offsets, limits here");
  scara->add_option("--controller", args->controller,
                    "mega: the Mega controller firmware driving the joint firmware, all on emulated chips, with "
                    "Robot Commands on a pty (test builds; docs/mega-controller.md)");
  scara->add_flag("--json", args->serve.json, "Log as JSON lines on stdout (started, log, stopped)");
  add_sim_scene_option(scara, args->scene);
  scara->add_option("--miscal", args->miscal,
                    "Mis-assemble the arm on purpose from this seed (0..4294967295): zeros shifted, one direction "
                    "flipped, link lengths off; the truth only in the debug log (ARMCTL_DEBUG=1)");
  scara->callback([args] { run_sim_scara(*args); });
}

}  // namespace armctl::cli

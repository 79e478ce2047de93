// armctl sim xarm: an emulated xArm board on a pty, until SIGINT/SIGTERM. `armctl emulate xarm`
// is the same command under its old name (deprecated: says so on stderr, then runs).
#include <cstdio>
#include <optional>
#include <string>

#include <fmt/core.h>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/number_options.hpp"
#include "apps/armctl/serve_support.hpp"
#include "apps/armctl/server_log.hpp"
#include "apps/armctl/sim_scene.hpp"
#include "core/debug_log.hpp"
#include "core/error.hpp"
#include "core/miscalibration.hpp"
#include "devices/xarm_emulator/emulator_runner.hpp"
#include "protocol/robot_commands/messages.hpp"
#include "transport/serial_port.hpp"

namespace armctl::cli {
namespace {

struct SimXarmArgs {
  std::string link;
  std::string state_dir;
  std::uint32_t baud = 9600;
  bool wire_timing = false;
  unsigned battery = 7500;
  bool json = false;
  std::string scene;  // --scene: what the arm meets
  std::string miscal;  // --miscal SEED: mis-assembled on purpose (core/miscalibration.hpp)
};

void run_sim_xarm(const SimXarmArgs& args) {
  if (args.battery < 4500 || args.battery > 12000)
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("--battery {} mV is outside 4500..12000", args.battery));
  xarm::EmulatorRunnerOptions options;
  if (!args.state_dir.empty()) options.emulator.state_dir = args.state_dir;
  options.emulator.battery_millivolts = static_cast<std::uint16_t>(args.battery);
  options.wire_timing = args.wire_timing;
  options.baud = args.baud;
  if (!args.miscal.empty()) {
    if (!args.state_dir.empty())
      throw ArmctlError(ErrorKind::invalid_argument,
                        "--miscal and --state-dir: a mis-assembled arm keeps nothing (it starts mis-assembled every time)");
    // The truth stays out of normal output: the wizard is there to find it.
    options.emulator.miscal = make_miscalibration(MiscalArm::xarm, parse_miscal_seed("--miscal", args.miscal).value());
    debug_log("sim xarm: " + describe(*options.emulator.miscal));
  }
  if (!args.scene.empty()) options.emulator.touches = sim_obstacle("xarm", arm::Protocol::robot_commands, args.scene);

  const ServerLog log("sim xarm", args.json);
  xarm::EmulatorRunner runner(options, [&log](const std::string& m) { log.line(m); });

  const PtySymlink symlink(args.link, runner.device_path());
  const StopOnSignals stop_on_signals(runner);

  log.started({{"servos", 6}, {"link", args.link}, {"wire_timing_baud", args.wire_timing ? args.baud : 0},
               {"scene", args.scene}},
              fmt::format("emulated xArm (servos 1..6) on {}{}{}{}; Ctrl-C to stop", runner.device_path(),
                          args.link.empty() ? "" : " linked from " + args.link,
                          args.wire_timing ? fmt::format(", wire timing {} baud", args.baud) : "",
                          args.scene.empty() ? "" : ", stopping at contact with " + args.scene),
              runner.device_path());

  runner.run();

  auto s = runner.stats();
  log.stopped({{"frames", s.frames}, {"handled", s.handled}, {"ignored", s.ignored()}, {"discarded_bytes", s.discarded_bytes}},
              fmt::format("sim xarm: stopped; {} frames, {} handled, {} ignored, {} bytes discarded", s.frames,
                          s.handled, s.ignored(), s.discarded_bytes));
}

void add_xarm_options(CLI::App& xarm, const std::shared_ptr<SimXarmArgs>& args) {
  xarm.add_option("--link", args->link, "Also create this symlink to the pty (removed on exit)");
  xarm.add_option("--state-dir", args->state_dir,
                  "Keep action groups and saved servo settings here (default: in memory)");
  xarm.add_option("--baud", args->baud, "Line rate for --wire-timing (default 9600)")
      ->check(standard_baud());
  xarm.add_flag("--wire-timing", args->wire_timing,
                "Bytes take as long as on a real 8N1 line at --baud");
  xarm.add_option("--battery", args->battery, "Battery voltage in mV, 4500..12000 (default 7500)")
      ->check(whole_number_in(rc::kMillivoltsMin, rc::kMillivoltsMax));
  xarm.add_flag("--json", args->json, "Log as JSON lines on stdout (started with the pty path, log, stopped)");
  add_sim_scene_option(&xarm, args->scene);
  xarm.add_option("--miscal", args->miscal,
                  "Mis-assemble the arm on purpose from this seed (0..4294967295): horns shifted, one servo "
                  "reversed, link lengths off, one servo ID duplicated; the truth only in the debug log (ARMCTL_DEBUG=1)");
}

constexpr const char* kXarmHelp =
    "An emulated xArm board (six bus servos) speaking Robot Commands on a pty; prints the pty "
    "path and runs until Ctrl-C";

}  // namespace

void add_sim_xarm_command(CLI::App& sim) {
  auto args = std::make_shared<SimXarmArgs>();
  auto* xarm = sim.add_subcommand("xarm", kXarmHelp);
  add_xarm_options(*xarm, args);
  xarm->callback([args] { run_sim_xarm(*args); });
}

void add_emulate_command(CLI::App& app) {
  auto* emulate = app.add_subcommand("emulate", "Deprecated: the old name of `armctl sim xarm`");
  emulate->require_subcommand(1);
  auto args = std::make_shared<SimXarmArgs>();
  auto* xarm = emulate->add_subcommand("xarm", std::string("Deprecated, use `armctl sim xarm`. ") + kXarmHelp);
  add_xarm_options(*xarm, args);
  xarm->callback([args] {
    fmt::print(stderr, "armctl: 'emulate xarm' is deprecated, use 'armctl sim xarm' (same options)\n");
    run_sim_xarm(*args);
  });
}

}  // namespace armctl::cli

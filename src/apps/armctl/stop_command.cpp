// armctl stop [--device URI] [--arm A]: stop every joint now, on any device, through the
// Arm API's stop: on the joint bus set_speed 0 to every joint back to back (each brakes at
// its own deceleration and holds); on Robot Commands GroupStop, then a hold where the
// servos stand.
#include <string>

#include <fmt/core.h>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/json_output.hpp"
#include "core/printable.hpp"
#include "session/arm_session.hpp"

namespace armctl::cli {

void add_stop_command(CLI::App& app) {
  struct Args {
    std::string device;
    std::string arm;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("stop", "Stop every joint at once and hold (any device)");
  cmd->add_option("--device", a->device, "Any device URI armctl knows (see armctl arm --help)");
  cmd->add_option("--arm", a->arm,
                  "xarm | scara | FILE (default: scara on a joint-bus URI, else xarm; use scara for "
                  "the arm controller)");
  cmd->add_flag("--json", a->json, "Machine-readable output: {\"event\": \"stopped\", \"device\": ...}");
  cmd->callback([a] {
    const std::string arm = !a->arm.empty() ? a->arm : (session::device_is_joint_bus(a->device) ? "scara" : "xarm");
    auto s = session::open_arm_session(arm, a->device).value();
    const auto stopped = s->arm->stop();
    if (!stopped) throw ArmctlError(stopped.error());
    if (a->json)
      print_json_line({{"event", "stopped"}, {"device", s->arm->device().description()}});
    else
      fmt::print("stopped: {}\n", printable(s->arm->device().description()));
  });
}

}  // namespace armctl::cli

// armctl controller --upstream URI [--bus URI] [--arm ARM] [--link PATH] [--state-dir DIR]
// The arm controller as a daemon: Robot Commands from a host on a pty or serial port,
// seven joints on the joint bus (docs/arm-controller.md).
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <utility>

#include <fmt/core.h>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/controller_serve.hpp"
#include "apps/armctl/server_log.hpp"
#include "devices/arm_controller/controller_config.hpp"
#include "transport/paced_link.hpp"
#include "devices/joint_bus/reconnecting_link.hpp"
#include "devices/device_registry/device_registry.hpp"

namespace armctl::cli {

namespace {

struct ControllerArgs {
  ControllerServeArgs serve;
  std::string bus = "sim";
  std::string arm;
};

void run_controller(const ControllerArgs& args) {
  auto config = controller_config_for(args.arm);
  std::shared_ptr<joint_bus::BusConnection> connection = devices::open_joint_bus(args.bus).value();
  if (transport::runs_on_simulated_time(connection->link())) {
    serve_controller(connection->link(), connection->default_options(), std::move(config), args.serve);
    return;
  }
  // A real link can close (`armctl sim scara` restarted under `--bus unix:...`, a USB-serial
  // adapter pulled out): the controller then reconnects with back-off instead of exiting
  // (docs/arm-controller.md "When the joint-bus link closes").
  const joint_bus::MasterOptions master_options = connection->default_options();
  auto open = [uri = args.bus, first = connection]() mutable -> std::shared_ptr<transport::JointBusLink> {
    std::shared_ptr<joint_bus::BusConnection> c =
        first ? std::exchange(first, nullptr) : std::shared_ptr<joint_bus::BusConnection>(devices::open_joint_bus(uri).value());
    return std::shared_ptr<transport::JointBusLink>(c, &c->link());  // the link lives as long as its connection
  };
  connection.reset();
  const SteadyClock clock;
  const ServerLog log(args.serve.label, args.serve.json);
  joint_bus::ReconnectingLink link(
      std::move(open), clock, [](TimePoint t) { std::this_thread::sleep_until(t); },
      [&log](const std::string& line) { log.line(line); });
  ControllerServeArgs serve = args.serve;
  serve.link_losses = [&link] { return link.losses(); };
  serve_controller(link, master_options, std::move(config), serve);
}

}  // namespace

void add_controller_command(CLI::App& app) {
  auto args = std::make_shared<ControllerArgs>();
  auto* c = app.add_subcommand(
      "controller", "The arm controller: Robot Commands upstream (pty or serial), the joint bus "
                    "downstream; prints the pty path and runs until Ctrl-C");
  c->add_option("--upstream", args->serve.upstream,
                "pty | serial:/dev/ttyS0[?baud=9600] | /dev/PATH (default pty)");
  c->add_option("--bus", args->bus,
                "Joint bus: sim[?baud=N&config=FILE] | unix:/path | serial:/dev/ttyAMA0?baud=N&select=... (default sim)");
  c->add_option("--arm", args->arm,
                "scara | an arm file: its arm_controller section (default scara, config/scara.arm.json)");
  c->add_option("--link", args->serve.link, "Also create this symlink to the pty (removed on exit)");
  c->add_option("--state-dir", args->serve.state_dir,
                "Keep action groups, offsets and limits here (default: in memory)");
  c->add_flag("--json", args->serve.json, "Log as JSON lines on stdout (started with the pty path, log, stopped)");
  c->callback([args] { run_controller(*args); });
}

}  // namespace armctl::cli

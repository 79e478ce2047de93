// armctl serve [--arm xarm|scara|FILE] [--device URI] [--listen 127.0.0.1:8080] [--token T]
// [--points FILE]: the web dashboard and its JSON HTTP API (docs/http-api.md) for one arm.
// Prints the URL (with the token off the loopback address) and serves until Ctrl-C, which
// stops the arm.
#include <charconv>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include <fmt/core.h>

#include "session/arm_session.hpp"
#include "apps/armctl/scene_option.hpp"
#include "apps/armctl/commands.hpp"
#include "apps/armctl/serve_support.hpp"
#include "apps/armctl/server_log.hpp"
#include "core/printable.hpp"
#include "core/regular_file.hpp"
#include "session/arm_worker.hpp"
#include "web/security.hpp"
#include "web/state_json.hpp"
#include "web/web_server.hpp"

namespace armctl::cli {

namespace {

struct ServeArgs {
  SceneArgs scene;  // --scene FILE, --fence, --reduced-mode
  std::string arm = "xarm";
  std::string device;
  std::string listen = "127.0.0.1:8080";
  std::string token;
  std::string points;
  bool json = false;
};

[[noreturn]] void usage(const std::string& message) { throw ArmctlError(ErrorKind::invalid_argument, message); }

// "HOST:PORT", "[V6]:PORT", "HOST" (port 8080), ":PORT" (127.0.0.1). Port 0: any free one.
std::pair<std::string, int> parse_listen(const std::string& text) {
  std::string host = text, port = "8080";
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string::npos) usage(fmt::format("--listen '{}': a ']' is missing", printable(text)));
    host = text.substr(1, close - 1);
    if (close + 1 < text.size()) {
      if (text[close + 1] != ':') usage(fmt::format("--listen '{}': expected ':PORT' after ']'", printable(text)));
      port = text.substr(close + 2);
    }
  } else if (const auto colon = text.rfind(':'); colon != std::string::npos) {
    if (text.find(':') != colon) usage(fmt::format("--listen '{}': write an IPv6 address as [ADDRESS]:PORT", printable(text)));
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
  }
  if (host.empty()) host = "127.0.0.1";
  int n = -1;
  auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), n);
  if (port.empty() || ec != std::errc() || end != port.data() + port.size() || n < 0 || n > 65535)
    usage(fmt::format("--listen '{}': the port '{}' is not allowed; 0..65535 (0: any free port)", printable(text),
                      printable(port)));
  return {host, n};
}

void run_serve(const ServeArgs& a) {
  const auto [host, port] = parse_listen(a.listen);
  web::ServerOptions options;
  options.host = host;
  options.port = port;
  options.token = a.token;
  if (options.token.empty() && !web::is_loopback(host)) options.token = web::make_token();
  if (!options.token.empty() && (options.token.size() < 8 || options.token.size() > 256 ||
                                 options.token.find_first_of(" \t\r\n&#?%") != std::string::npos))
    usage("--token: 8..256 characters without spaces or any of & # ? % (it goes into a URL)");
  options.points_file = a.points;

  // The embedded simulated bus in step with the wall clock, like a real arm: people watch it.
  session::SessionOptions session_options = with_scene(a.scene);
  session_options.wall_clock = true;
  session_options.reconnect = true;  // a restarted simulator or a replugged adapter is picked up again
  auto session = armctl::session::open_arm_session(a.arm, a.device, session_options).value();
  const arm::ArmModel& model = session->arm->model();
  options.device = web::describe_device(*session, a.device);
  const std::string arm_name = model.name;

  session::ArmWorker worker(std::move(session));
  web::WebServer server(worker, options);
  server.start();
  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);  // before the URL is said: Ctrl-C from then on stops cleanly
  const ServerLog log("armctl serve", a.json, stdout);
  log.started({{"arm", arm_name}, {"arm_device", printable(options.device.description)}, {"url", server.url()}},
              fmt::format("armctl serve: arm {} on {}\nopen {}\n(Ctrl-C stops the arm and the server)", arm_name,
                          printable(options.device.description), server.url()));

  // The signal handler only sets the flag; stopping the server is not async-signal-safe.
  while (!interrupted) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  worker.command(arm::MotionCommand::stop);
  server.stop();
  log.stopped({}, "stopped");
}

}  // namespace

void add_serve_command(CLI::App& app) {
  auto a = std::make_shared<ServeArgs>();
  auto* cmd = app.add_subcommand("serve", "The web dashboard and its JSON HTTP API for one arm (docs/http-api.md)");
  cmd->footer(
      "Listens on the loopback address by default. On any other address every request needs a\n"
      "token (made up at start unless --token gives one; part of the printed URL). Without\n"
      "--device: the embedded simulated arm (see armctl arm --help).");
  add_arm_options(cmd, a->arm, a->device);
  add_scene_option(cmd, a->scene);
  cmd->add_option("--listen", a->listen, "HOST:PORT (default 127.0.0.1:8080; port 0: any free port)");
  cmd->add_option("--token", a->token, "The access token (default: made up off the loopback address)");
  cmd->add_option("--points", a->points, "Points file the dashboard records points into (program format)");
  cmd->add_flag("--json", a->json, "Say where it listens, and that it stopped, as JSON lines on stdout");
  cmd->callback([a] { run_serve(*a); });
}

}  // namespace armctl::cli

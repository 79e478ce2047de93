#include "apps/armctl/xarm_session.hpp"

#include <cstdlib>

#include "core/error.hpp"

#include "devices/robot_commands/device_uri.hpp"
#include "devices/robot_commands/stream_link.hpp"
#include "transport/serial_port.hpp"

namespace armctl::cli {

std::filesystem::path embedded_state_dir() {
  namespace fs = std::filesystem;
  auto env = [](const char* name) -> std::string {
    const char* v = std::getenv(name);
    return v ? std::string(v) : std::string();
  };
  if (auto dir = env("ARMCTL_STATE_DIR"); !dir.empty()) return fs::path(dir) / "xarm-emulator";
  // XDG base directories: a relative XDG_STATE_HOME is invalid and must be ignored.
  if (auto xdg = env("XDG_STATE_HOME"); !xdg.empty() && fs::path(xdg).is_absolute())
    return fs::path(xdg) / "armctl" / "xarm-emulator";
  if (auto home = env("HOME"); !home.empty())
    return fs::path(home) / ".local" / "state" / "armctl" / "xarm-emulator";
  throw ArmctlError(ErrorKind::invalid_config,
                    "no state directory for the embedded emulated xArm: HOME is not set (set "
                    "ARMCTL_STATE_DIR or XDG_STATE_HOME, or use --device)");
}

XarmSession::~XarmSession() {
  // The embedded board ends with this command. Commands without a reply (move, offset save,
  // info write, group speed, ...) may still sit unread in the pty: one request with a reply
  // first, answered only after every earlier frame was handled, so none is lost.
  if (emulator && client) (void)client->battery_millivolts();
  client.reset();
  link.reset();
  if (emulator) emulator->stop();
}

std::unique_ptr<XarmSession> open_xarm_session(const std::string& device, int servo_count,
                                               int timeout_ms) {
  auto s = std::make_unique<XarmSession>();
  if (device.empty()) {
    // The embedded board lives as long as this command, but keeps what a real board keeps
    // (action groups, saved offsets, servo limits) in a per-user state directory, so
    // `group download` and a later `group run` meet the same stored group. Servo positions
    // are not stored: every command starts with the servos at centre.
    xarm::EmulatorRunnerOptions options;
    options.emulator.state_dir = embedded_state_dir();
    s->emulator = std::make_unique<xarm::EmulatorRunner>(options);
    s->emulator->start();
    s->link = std::make_unique<robot_commands::StreamLink>(
        transport::SerialPort::open(s->emulator->device_path()),
        "embedded emulated xArm on " + s->emulator->device_path());
  } else {
    auto uri = robot_commands::parse_device_uri(device);
    s->link = robot_commands::open_link(uri.value());  // value() throws the parse error
  }
  robot_commands::ClientOptions options;
  options.servo_count = servo_count;
  options.reply_timeout = std::chrono::milliseconds(timeout_ms);
  options.download_timeout = std::chrono::milliseconds(std::max(timeout_ms, 2000));
  s->client = std::make_unique<robot_commands::Client>(*s->link, options);
  return s;
}

}  // namespace armctl::cli

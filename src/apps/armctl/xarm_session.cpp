#include "apps/armctl/xarm_session.hpp"

#include "devices/robot_commands/device_uri.hpp"
#include "devices/robot_commands/stream_link.hpp"
#include "transport/serial_port.hpp"

namespace armctl::cli {

XarmSession::~XarmSession() {
  client.reset();
  link.reset();
  if (emulator) emulator->stop();
}

std::unique_ptr<XarmSession> open_xarm_session(const std::string& device, int servo_count,
                                               int timeout_ms) {
  auto s = std::make_unique<XarmSession>();
  if (device.empty()) {
    // The embedded board keeps nothing after this command ends (no state directory); use
    // `armctl emulate xarm` for a long-lived one with stored groups.
    s->emulator = std::make_unique<xarm::EmulatorRunner>(xarm::EmulatorRunnerOptions{});
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

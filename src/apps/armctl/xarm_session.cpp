#include "apps/armctl/xarm_session.hpp"

namespace armctl::cli {

XarmSession::~XarmSession() {
  // The embedded board ends with this command. Commands without a reply (move, offset save,
  // info write, group speed, ...) may still sit unread in the pty: one request with a reply
  // first, answered only after every earlier frame was handled, so none is lost.
  if (connection && connection->embedded() && client) (void)client->battery_millivolts();
  client.reset();
  connection.reset();
}

std::unique_ptr<XarmSession> open_xarm_session(const std::string& device, int servo_count,
                                               int timeout_ms) {
  auto s = std::make_unique<XarmSession>();
  // value() throws the error for main() to print: the CLI's one exception path.
  s->connection = devices::open_robot_commands(device.empty() ? "sim" : device).value();
  robot_commands::ClientOptions options;
  options.servo_count = servo_count;
  options.reply_timeout = std::chrono::milliseconds(timeout_ms);
  options.download_timeout = std::chrono::milliseconds(std::max(timeout_ms, 2000));
  s->client = std::make_unique<robot_commands::Client>(s->connection->link(), options);
  return s;
}

}  // namespace armctl::cli

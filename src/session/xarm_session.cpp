#include "session/xarm_session.hpp"

#include <fmt/core.h>

#include "core/printable.hpp"
#include "devices/robot_commands/hid_link.hpp"

namespace armctl::session {

XarmSession::~XarmSession() {
  // The embedded board ends with this command. Commands without a reply (move, offset save,
  // info write, group speed, ...) may still sit unread in the pty: one request with a reply
  // first, answered only after every earlier frame was handled, so none is lost.
  if (connection && connection->embedded() && client) (void)client->battery_millivolts();
  client.reset();
  connection.reset();
}

Result<bool> XarmSession::confirm_accepted(const std::string& what) {
  if (!connection->embedded()) return false;
  // Answered only after every earlier frame was handled: the board's log is then complete.
  if (auto battery = client->battery_millivolts(); !battery) return check(battery.error()).error();
  const auto log = connection->take_board_log();
  if (log.empty()) return true;
  std::string why;
  for (const auto& line : log) why += (why.empty() ? "" : "; ") + line;
  return Error{ErrorKind::device, fmt::format("{}: the board refused it: {}", what, why)};
}

Status XarmSession::check(Status status) {
  if (status) return status;
  Error error = status.error();
  if (connection->embedded()) {
    for (const auto& line : connection->take_board_log()) error.message += "; the board logged: " + line;
  }
  return error;
}

Result<std::unique_ptr<XarmSession>> open_xarm_session(const std::string& device, int servo_count,
                                                       int timeout_ms) {
  auto s = std::make_unique<XarmSession>();
  auto connection = devices::open_robot_commands(device.empty() ? "sim" : device);
  if (!connection) return connection.error();
  s->connection = std::move(connection).value();
  auto* hid = dynamic_cast<robot_commands::HidLink*>(&s->connection->link());
  robot_commands::ClientOptions options =
      hid ? robot_commands::hid_client_options(servo_count) : robot_commands::ClientOptions{};
  options.servo_count = servo_count;
  // The embedded board is ours: it handles a combined MultiServoOff (docs/usb-hid.md).
  if (s->connection->embedded()) options.servo_off_per_servo = false;
  if (timeout_ms > 0) options.reply_timeout = std::chrono::milliseconds(timeout_ms);
  options.download_timeout = std::max<Duration>(options.reply_timeout, options.download_timeout);
  // The client's constructor refuses a servo count outside 1..19 by throwing.
  auto client = catch_error([&]() -> Result<std::unique_ptr<robot_commands::Client>> {
    return std::make_unique<robot_commands::Client>(s->connection->link(), options);
  });
  if (!client) return client.error();
  s->client = std::move(client).value();
  // What the embedded board found wrong in its state dir at start (a leftover temporary file it
  // could not remove, a skipped odd entry): reported, not fatal.
  for (const auto& line : s->connection->take_board_log())
    fmt::print(stderr, "armctl: warning: embedded xArm: {}\n", printable(line));
  if (hid) {
    for (const auto& w : hid->warnings()) fmt::print(stderr, "armctl: warning: {}\n", printable(w));
    if (auto contact = robot_commands::await_first_contact(*s->client); !contact) return contact.error();
  }
  return s;
}

}  // namespace armctl::session

#include "devices/robot_commands/device_uri.hpp"

#include <charconv>

#include "devices/robot_commands/hid_link.hpp"
#include "devices/robot_commands/stream_link.hpp"
#include "transport/serial_port.hpp"

namespace armctl::robot_commands {
namespace {

constexpr const char* kForms =
    "allowed: hid, hid:SERIAL, hid:/dev/hidrawN, serial:/dev/PATH[?baud=N], /dev/PATH";

Error bad(const std::string& why) {
  return Error{ErrorKind::invalid_argument, why + " (" + kForms + ")"};
}

}  // namespace

Result<DeviceUri> parse_device_uri(const std::string& text) {
  DeviceUri uri;
  if (text == "hid") {
    uri.kind = DeviceUri::Kind::hid;
    return uri;
  }
  if (text.rfind("hid:", 0) == 0) {
    uri.kind = DeviceUri::Kind::hid;
    uri.target = text.substr(4);
    if (uri.target.empty()) return bad("device \"hid:\" names no board");
    return uri;
  }
  std::string rest;
  if (text.rfind("serial:", 0) == 0) {
    rest = text.substr(7);
  } else if (text.rfind("/dev/", 0) == 0 || text.rfind("/", 0) == 0) {
    rest = text;
  } else {
    return bad("device \"" + text + "\" is not understood");
  }
  const auto q = rest.find('?');
  uri.kind = DeviceUri::Kind::serial;
  uri.target = rest.substr(0, q);
  if (uri.target.empty() || uri.target[0] != '/') {
    return bad("device \"" + text + "\" needs an absolute serial port path");
  }
  if (q != std::string::npos) {
    const std::string option = rest.substr(q + 1);
    if (option.rfind("baud=", 0) != 0) {
      return bad("device \"" + text + "\": unknown option \"" + option + "\" (only baud=N)");
    }
    const std::string value = option.substr(5);
    std::uint32_t baud = 0;
    auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), baud);
    if (ec != std::errc{} || end != value.data() + value.size() ||
        !transport::baud_constant(baud)) {
      return Error{ErrorKind::invalid_argument,
                   "device \"" + text + "\": baud \"" + value +
                       "\" is not a standard rate (allowed: " + transport::standard_bauds_text() +
                       ")"};
    }
    uri.baud = baud;
  }
  return uri;
}

std::unique_ptr<RcLink> open_link(const DeviceUri& uri) {
  if (uri.kind == DeviceUri::Kind::hid) return HidLink::open_board(uri.target);
  auto port = transport::SerialPort::open(uri.target, uri.baud);
  const std::string description =
      "serial:" + uri.target + " at " + std::to_string(uri.baud) + " baud";
  return std::make_unique<StreamLink>(std::move(port), description);
}

}  // namespace armctl::robot_commands

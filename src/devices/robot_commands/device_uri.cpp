#include "devices/robot_commands/device_uri.hpp"

#include "core/miscalibration.hpp"
#include "devices/robot_commands/hid_link.hpp"
#include "devices/robot_commands/stream_link.hpp"
#include "transport/device_uri_parts.hpp"
#include "transport/serial_port.hpp"

namespace armctl::robot_commands {
namespace {

constexpr const char* kForms =
    "sim, sim?miscal=SEED, hid, hid:SERIAL, hid:/dev/hidrawN, serial:/dev/PATH[?baud=N], /dev/PATH";

Error bad(const std::string& text, const std::string& why) {
  return transport::uri_error(text, Error{ErrorKind::invalid_argument, why}, kForms);
}

}  // namespace

Result<DeviceUri> parse_device_uri(const std::string& text) {
  auto parts = transport::split_uri(text);
  if (!parts) return transport::uri_error(text, parts.error(), kForms);
  DeviceUri uri;
  if (parts->kind == "sim" || parts->kind == "hid") {
    uri.kind = parts->kind == "sim" ? DeviceUri::Kind::sim : DeviceUri::Kind::hid;
    const bool sim = uri.kind == DeviceUri::Kind::sim;
    if (auto known = transport::check_options(*parts, sim ? std::initializer_list<std::string_view>{"miscal"}
                                                          : std::initializer_list<std::string_view>{});
        !known)
      return transport::uri_error(text, known.error(), kForms);
    if (sim && parts->has_path) return bad(text, "sim takes no path");
    if (sim && parts->options.contains("miscal")) {
      auto seed = parse_miscal_seed("miscal", parts->options["miscal"]);
      if (!seed) return transport::uri_error(text, seed.error(), kForms);
      uri.miscal = *seed;
    }
    uri.target = parts->path;
    if (uri.kind == DeviceUri::Kind::hid && parts->has_path && uri.target.empty()) {
      return bad(text, "\"hid:\" names no board");
    }
    return uri;
  }
  if (parts->kind != "serial") return bad(text, "unknown kind of device");
  auto serial = transport::parse_serial_uri(*parts, transport::kDefaultBaud);
  if (!serial) return transport::uri_error(text, serial.error(), kForms);
  uri.kind = DeviceUri::Kind::serial;
  uri.target = serial->path;
  uri.baud = serial->baud;
  return uri;
}

Result<std::unique_ptr<RcLink>> open_link(const DeviceUri& uri) {
  if (uri.kind == DeviceUri::Kind::sim) {
    return Error{ErrorKind::unsupported,
                 "device \"sim\" (the embedded emulated xArm) is a simulator: open it with "
                 "devices::open_robot_commands (library armctl_device_registry)"};
  }
  // Opening is done by constructors, which throw; this is where that becomes a Result.
  return catch_error([&]() -> Result<std::unique_ptr<RcLink>> {
    if (uri.kind == DeviceUri::Kind::hid) return {HidLink::open_board(uri.target)};
    auto port = transport::SerialPort::open(uri.target, uri.baud);
    const std::string description =
        "serial:" + uri.target + " at " + std::to_string(uri.baud) + " baud";
    return {std::make_unique<StreamLink>(std::move(port), description, uri.baud)};
  });
}

}  // namespace armctl::robot_commands

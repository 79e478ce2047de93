// The Robot Commands `--device` URI parser (devices/robot_commands/device_uri.hpp) on
// arbitrary text: an error of kind invalid_argument listing the accepted forms, or a
// device with a usable target (absolute serial path without options, standard baud; a
// named HID board unless the URI was plain `hid`; nothing for `sim`, the embedded board).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "devices/robot_commands/device_uri.hpp"
#include "transport/serial_port.hpp"

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_rc_device_uri: accepted URI breaks: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using armctl::robot_commands::DeviceUri;
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (text.find('\0') != std::string::npos) return 0;  // argv cannot hold a NUL byte
  const auto r = armctl::robot_commands::parse_device_uri(text);
  if (!r.ok()) {
    check(r.error().kind == armctl::ErrorKind::invalid_argument, "error kind invalid_argument");
    check(r.error().message.find("allowed") != std::string::npos, "error lists what is allowed");
    return 0;
  }
  const DeviceUri& d = *r;
  if (d.kind == DeviceUri::Kind::hid) {
    // `hid` (or `hid?`): the first board; `hid:X`: board X, never empty.
    check(d.target.empty() == (text.find(':') == std::string::npos), "hid target");
  } else if (d.kind == DeviceUri::Kind::sim) {
    check(text.rfind("sim", 0) == 0 && d.target.empty(), "sim has no target");
    check(text.find(':') == std::string::npos, "sim takes no path");
  } else {
    check(!d.target.empty() && d.target[0] == '/', "serial path absolute");
    check(d.target.find('?') == std::string::npos, "no options left in the path");
    check(armctl::transport::baud_constant(d.baud).has_value(), "baud standard");
  }
  return 0;
}

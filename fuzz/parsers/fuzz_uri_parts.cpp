// The one parser of device URI text (transport/device_uri_parts.hpp) on arbitrary text:
// split_uri either refuses with invalid_argument or gives options whose keys are non-empty
// and hold no '&' or '='; parse_serial_uri (with the joint bus's extra options) either
// refuses or gives an absolute path with no '?' and a standard baud, and only the extra
// options it was told about.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "transport/device_uri_parts.hpp"
#include "transport/serial_port.hpp"

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_uri_parts: accepted URI breaks: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl::transport;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (text.find('\0') != std::string_view::npos) return 0;  // argv cannot hold a NUL byte
  const auto parts = split_uri(text);
  if (!parts) {
    check(parts.error().kind == armctl::ErrorKind::invalid_argument, "error kind invalid_argument");
    return 0;
  }
  for (const auto& [key, value] : parts->options) {
    check(!key.empty(), "option key non-empty");
    check(key.find_first_of("&=") == std::string::npos, "option key holds no & or =");
    check(value.find('&') == std::string::npos, "option value holds no &");
  }
  check(parts->path.find('?') == std::string::npos, "no query left in the path");
  const auto serial = parse_serial_uri(*parts, kDefaultBaud, {"chip", "select"});
  if (!serial) {
    check(serial.error().kind == armctl::ErrorKind::invalid_argument, "serial error kind");
    const auto e = uri_error(text, serial.error(), "serial:/dev/PATH[?baud=N]");
    check(e.message.find("allowed: serial:") != std::string::npos, "uri_error names the forms");
    return 0;
  }
  check(!serial->path.empty() && serial->path[0] == '/', "serial path absolute");
  check(baud_constant(serial->baud).has_value(), "serial baud standard");
  for (const auto& [key, value] : serial->options) check(key == "chip" || key == "select", "only extra options kept");
  return 0;
}

// The joint-bus `--device` URI parser (devices/joint_bus/device_uri.hpp) on arbitrary
// text. It must return an invalid_argument error naming the URI, or a device
// whose every field is usable: standard baud rates, 1..7 distinct select lines, absolute
// serial paths, non-empty names. describe() must work on anything accepted.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string_view>
#include <variant>

#include "core/error.hpp"
#include "devices/joint_bus/device_uri.hpp"
#include "transport/serial_port.hpp"

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_bus_device_uri: accepted URI breaks: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl::joint_bus;
  const std::string_view uri(reinterpret_cast<const char*>(data), size);
  // URIs come from argv, which cannot hold a NUL byte.
  if (uri.find('\0') != std::string_view::npos) return 0;
  const auto parsed = parse_device_uri(uri);
  if (!parsed) {
    const armctl::Error& e = parsed.error();
    check(e.kind == armctl::ErrorKind::invalid_argument, "error kind invalid_argument");
    check(e.message.find("allowed") != std::string::npos, "error lists the allowed forms");
    return 0;
  }
  {
    const DeviceUri& d = *parsed;
    if (const auto* s = std::get_if<SimDevice>(&d)) {
      check(!s->baud || armctl::transport::baud_constant(*s->baud).has_value(), "sim baud standard");
      check(uri.starts_with("sim"), "sim from sim");
    } else if (const auto* u = std::get_if<UnixDevice>(&d)) {
      check(!u->path.empty() && u->path.find('?') == std::string::npos, "unix path");
    } else {
      const auto& s = std::get<SerialDevice>(d);
      check(!s.path.empty() && s.path[0] == '/' && s.path.find('?') == std::string::npos,
            "serial path absolute");
      check(armctl::transport::baud_constant(s.baud).has_value(), "serial baud standard");
      check(!s.chip.empty(), "chip named");
      check(!s.select.empty() && s.select.size() <= 7, "1..7 select lines");
      std::set<unsigned> lines(s.select.begin(), s.select.end());
      check(lines.size() == s.select.size(), "select lines distinct");
    }
    check(!describe(d).empty(), "describe");
  }
  return 0;
}

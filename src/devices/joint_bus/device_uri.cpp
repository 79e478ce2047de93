#include "devices/joint_bus/device_uri.hpp"

#include <charconv>
#include <map>
#include <set>

#include <fmt/core.h>

#include "core/error.hpp"
#include "transport/serial_port.hpp"

namespace armctl::joint_bus {

namespace {

constexpr const char* kForms =
    "sim, sim?baud=N&config=FILE&dead=J[,J...], unix:/path/to/socket, or "
    "serial:/dev/ttyAMA0?select=17,27,22,5,6,13,19[&baud=9600][&chip=gpiochip0][&dialect=legacy]";

[[noreturn]] void bad(std::string_view uri, const std::string& why) {
  throw ArmctlError(ErrorKind::invalid_argument,
                    fmt::format("device '{}': {} (allowed: {})", uri, why, kForms));
}

std::map<std::string, std::string> parse_query(std::string_view uri, std::string_view query,
                                               const std::set<std::string>& allowed) {
  std::map<std::string, std::string> out;
  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view item = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    const auto eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0) bad(uri, fmt::format("option '{}' is not key=value", item));
    std::string key(item.substr(0, eq));
    if (!allowed.contains(key)) {
      std::string names;
      for (const auto& a : allowed) names += (names.empty() ? "" : ", ") + a;
      bad(uri, fmt::format("unknown option '{}' (this device takes: {})", key, names));
    }
    if (out.contains(key)) bad(uri, fmt::format("option '{}' given twice", key));
    out[key] = std::string(item.substr(eq + 1));
  }
  return out;
}

unsigned parse_unsigned(std::string_view uri, const std::string& what, std::string_view text, unsigned max) {
  unsigned v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size() || v > max) {
    bad(uri, fmt::format("{} '{}' is not a whole number 0..{}", what, text, max));
  }
  return v;
}

std::uint32_t parse_baud(std::string_view uri, std::string_view text) {
  const unsigned b = parse_unsigned(uri, "baud", text, 4'000'000);
  if (!transport::baud_constant(b)) {
    bad(uri, fmt::format("baud {} is not a standard rate ({})", b, transport::standard_bauds_text()));
  }
  return b;
}

}  // namespace

DeviceUri parse_device_uri(std::string_view uri) {
  const auto q = uri.find('?');
  const std::string_view head = uri.substr(0, q);
  const std::string_view query = q == std::string_view::npos ? std::string_view{} : uri.substr(q + 1);

  if (head == "sim") {
    SimDevice d;
    auto opts = parse_query(uri, query, {"baud", "config", "dead"});
    if (opts.contains("baud")) d.baud = parse_baud(uri, opts["baud"]);
    if (opts.contains("dead")) {
      std::string_view list = opts["dead"];
      while (true) {
        const auto comma = list.find(',');
        const std::string_view item = list.substr(0, comma);
        unsigned joint = 0;
        const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), joint);
        if (item.empty() || ec != std::errc{} || end != item.data() + item.size() || joint < 1 ||
            joint > 7) {
          bad(uri, fmt::format("dead joint '{}' is not a joint (allowed 1..7, comma-separated)", item));
        }
        d.dead_joints.push_back(static_cast<int>(joint));
        if (comma == std::string_view::npos) break;
        list.remove_prefix(comma + 1);
      }
    }
    if (opts.contains("config")) {
      if (opts["config"].empty()) bad(uri, "config needs a file path");
      d.config = opts["config"];
    }
    return d;
  }
  if (head.starts_with("unix:")) {
    UnixDevice d{std::string(head.substr(5))};
    if (d.path.empty()) bad(uri, "unix: needs a socket path");
    if (q != std::string_view::npos) bad(uri, "unix: takes no options");
    return d;
  }
  if (head.starts_with("serial:")) {
    SerialDevice d;
    d.path = std::string(head.substr(7));
    if (d.path.empty() || d.path[0] != '/') bad(uri, "serial: needs an absolute device path such as /dev/ttyAMA0");
    auto opts = parse_query(uri, query, {"baud", "chip", "select", "dialect"});
    if (opts.contains("baud")) d.baud = parse_baud(uri, opts["baud"]);
    if (opts.contains("chip")) {
      if (opts["chip"].empty()) bad(uri, "chip needs a GPIO chip name such as gpiochip0");
      d.chip = opts["chip"];
    }
    if (opts.contains("dialect")) {
      auto dialect = dialect_from_string(opts["dialect"]);
      if (!dialect) bad(uri, fmt::format("dialect '{}' is neither standard nor legacy", opts["dialect"]));
      d.dialect = *dialect;
    }
    if (!opts.contains("select")) bad(uri, "serial: needs select=LINE,... (one GPIO line per joint, joint 1 first)");
    std::string_view list = opts["select"];
    std::set<unsigned> seen;
    while (true) {
      const auto comma = list.find(',');
      const unsigned line = parse_unsigned(uri, "select line", list.substr(0, comma), 1023);
      if (!seen.insert(line).second) bad(uri, fmt::format("select line {} is given twice", line));
      d.select.push_back(line);
      if (comma == std::string_view::npos) break;
      list = list.substr(comma + 1);
    }
    if (d.select.size() > 7) bad(uri, fmt::format("{} select lines given: the joint bus has 1..7 joints", d.select.size()));
    return d;
  }
  bad(uri, "unknown kind of device");
}

std::string describe(const DeviceUri& uri) {
  if (const auto* s = std::get_if<SimDevice>(&uri)) {
    return s->baud ? fmt::format("embedded simulated arm at {} baud", *s->baud)
                   : std::string("embedded simulated arm");
  }
  if (const auto* u = std::get_if<UnixDevice>(&uri)) return fmt::format("simulated arm at {}", u->path);
  const auto& s = std::get<SerialDevice>(uri);
  return fmt::format("serial {} at {} baud, select lines on {}", s.path, s.baud, s.chip);
}

}  // namespace armctl::joint_bus

#include "devices/joint_bus/device_uri.hpp"

#include <charconv>
#include <set>

#include <fmt/core.h>

#include "core/error.hpp"
#include "core/miscalibration.hpp"
#include "transport/device_uri_parts.hpp"

namespace armctl::joint_bus {

namespace {

constexpr const char* kForms =
    "sim, sim?baud=N&config=FILE&dead=J[,J...]&dialect=legacy&miscal=SEED, unix:/path/to/socket, or "
    "serial:/dev/ttyAMA0?select=17,27,22,5,6,13,19[&baud=9600][&chip=gpiochip0][&dialect=legacy]";

[[noreturn]] void bad(std::string_view uri, const std::string& why) {
  throw ArmctlError(transport::uri_error(uri, Error{ErrorKind::invalid_argument, why}, kForms));
}

template <typename T>
T checked(std::string_view uri, Result<T> r) {
  if (!r) throw ArmctlError(transport::uri_error(uri, r.error(), kForms));
  return std::move(r).value();
}

unsigned parse_unsigned(std::string_view uri, const std::string& what, std::string_view text, unsigned max) {
  unsigned v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size() || v > max) {
    bad(uri, fmt::format("{} '{}' is not a whole number 0..{}", what, text, max));
  }
  return v;
}

Dialect parse_dialect(std::string_view uri, const std::string& text) {
  auto dialect = dialect_from_string(text);
  if (!dialect) bad(uri, fmt::format("dialect '{}' is neither standard nor legacy", text));
  return *dialect;
}

// "2,6": joints 1..7, comma-separated (the sim's dead= and swapped=).
std::vector<int> parse_joint_list(std::string_view uri, const char* what, std::string_view list) {
  std::vector<int> joints;
  while (true) {
    const auto comma = list.find(',');
    const std::string_view item = list.substr(0, comma);
    unsigned joint = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), joint);
    if (item.empty() || ec != std::errc{} || end != item.data() + item.size() || joint < 1 || joint > 7) {
      bad(uri, fmt::format("{} joint '{}' is not a joint (allowed 1..7, comma-separated)", what, item));
    }
    joints.push_back(static_cast<int>(joint));
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return joints;
}

SimDevice parse_sim(std::string_view uri, transport::UriParts& parts) {
  if (parts.has_path) bad(uri, "sim takes options after '?', not a path");
  checked(uri, transport::check_options(parts, {"baud", "config", "dead", "dialect", "miscal", "swapped"}));
  SimDevice d;
  auto& opts = parts.options;
  if (opts.contains("baud")) d.baud = checked(uri, transport::parse_baud(opts["baud"]));
  if (opts.contains("dialect")) d.dialect = parse_dialect(uri, opts["dialect"]);
  if (opts.contains("dead")) d.dead_joints = parse_joint_list(uri, "dead", opts["dead"]);
  if (opts.contains("swapped")) d.swapped_joints = parse_joint_list(uri, "swapped", opts["swapped"]);
  if (opts.contains("miscal")) d.miscal = checked(uri, parse_miscal_seed("miscal", opts["miscal"]));
  if (opts.contains("config")) {
    if (opts["config"].empty()) bad(uri, "config needs a file path");
    d.config = opts["config"];
  }
  return d;
}

SerialDevice parse_serial(std::string_view uri, const transport::UriParts& parts) {
  auto serial = checked(uri, transport::parse_serial_uri(parts, 9600, {"chip", "select", "dialect"}));
  SerialDevice d;
  d.path = serial.path;
  d.baud = serial.baud;
  auto& opts = serial.options;
  if (opts.contains("chip")) {
    if (opts["chip"].empty()) bad(uri, "chip needs a GPIO chip name such as gpiochip0");
    d.chip = opts["chip"];
  }
  if (opts.contains("dialect")) d.dialect = parse_dialect(uri, opts["dialect"]);
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

// Every check unwinds through bad(); parse_device_uri turns that into the returned error.
DeviceUri parse_or_throw(std::string_view uri) {
  auto parts = checked(uri, transport::split_uri(uri));
  if (parts.kind == "sim") return parse_sim(uri, parts);
  if (parts.kind == "unix") {
    UnixDevice d{parts.path};
    if (d.path.empty()) bad(uri, "unix: needs a socket path");
    if (parts.has_query) bad(uri, "unix: takes no options");
    return d;
  }
  if (parts.kind == "serial") return parse_serial(uri, parts);
  bad(uri, "unknown kind of device");
}

}  // namespace

Result<DeviceUri> parse_device_uri(std::string_view uri) {
  return catch_error([&]() -> Result<DeviceUri> { return parse_or_throw(uri); });
}

std::string describe(const DeviceUri& uri) {
  if (const auto* s = std::get_if<SimDevice>(&uri)) {
    const std::string legacy = std::string(s->dialect == Dialect::legacy ? ", legacy-master joints" : "") +
                               (s->miscal ? ", mis-assembled" : "");
    return s->baud ? fmt::format("embedded simulated arm at {} baud{}", *s->baud, legacy)
                   : "embedded simulated arm" + legacy;
  }
  if (const auto* u = std::get_if<UnixDevice>(&uri)) return fmt::format("simulated arm at {}", u->path);
  const auto& s = std::get<SerialDevice>(uri);
  return fmt::format("serial {} at {} baud, select lines on {}", s.path, s.baud, s.chip);
}

}  // namespace armctl::joint_bus

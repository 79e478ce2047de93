#include "transport/device_uri_parts.hpp"

#include <charconv>
#include <vector>

#include <fmt/core.h>

#include "core/printable.hpp"
#include "transport/serial_port.hpp"

namespace armctl::transport {

namespace {

Error bad(std::string why) { return Error{ErrorKind::invalid_argument, std::move(why)}; }

Status check_keys(const UriParts& parts, const std::vector<std::string_view>& allowed) {
  for (const auto& [key, value] : parts.options) {
    bool known = false;
    for (std::string_view a : allowed) known = known || a == key;
    if (known) continue;
    if (allowed.empty()) return bad(fmt::format("unknown option '{}' ({} takes no options)", printable(key), printable(parts.kind)));
    std::string names;
    for (std::string_view a : allowed) names += fmt::format("{}{}", names.empty() ? "" : ", ", a);
    return bad(fmt::format("unknown option '{}' (this device takes: {})", printable(key), names));
  }
  return Ok{};
}

}  // namespace

Result<UriParts> split_uri(std::string_view uri) {
  UriParts parts;
  const auto q = uri.find('?');
  const std::string_view head = uri.substr(0, q);
  parts.has_query = q != std::string_view::npos;
  if (head.starts_with('/')) {
    parts.kind = "serial";
    parts.path = std::string(head);
    parts.has_path = true;
  } else {
    const auto colon = head.find(':');
    parts.kind = std::string(head.substr(0, colon));
    if (colon != std::string_view::npos) {
      parts.path = std::string(head.substr(colon + 1));
      parts.has_path = true;
    }
  }
  // "sim?" is "sim"; every item after that must be key=value ("sim?baud=9600&" is not).
  std::string_view query = parts.has_query ? uri.substr(q + 1) : std::string_view{};
  bool more = !query.empty();
  while (more) {
    const auto amp = query.find('&');
    const std::string_view item = query.substr(0, amp);
    more = amp != std::string_view::npos;
    query = more ? query.substr(amp + 1) : std::string_view{};
    const auto eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0) return bad(fmt::format("option '{}' is not key=value", printable(item)));
    std::string key(item.substr(0, eq));
    if (parts.options.contains(key)) return bad(fmt::format("option '{}' given twice", printable(key)));
    parts.options[key] = std::string(item.substr(eq + 1));
  }
  return parts;
}

Status check_options(const UriParts& parts, std::initializer_list<std::string_view> allowed) {
  return check_keys(parts, std::vector<std::string_view>(allowed));
}

Result<std::uint32_t> parse_baud(std::string_view text) {
  std::uint32_t baud = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), baud);
  if (ec == std::errc::result_out_of_range && end == text.data() + text.size()) {
    return bad(fmt::format("baud {} is outside 1..{} (standard rates: {})", printable(text), kMaxStandardBaud,
                           standard_bauds_text()));
  }
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size()) {
    return bad(fmt::format("baud '{}' is not a whole number (standard rates: {})", printable(text),
                           standard_bauds_text()));
  }
  if (!baud_constant(baud)) {
    return bad(fmt::format("baud {} is not a standard rate ({})", baud, standard_bauds_text()));
  }
  return baud;
}

Result<SerialUri> parse_serial_uri(const UriParts& parts, std::uint32_t default_baud,
                                   std::initializer_list<std::string_view> extra) {
  if (parts.kind != "serial") return bad(fmt::format("'{}' is not a serial port", printable(parts.kind)));
  if (parts.path.empty() || parts.path[0] != '/') {
    return bad("serial: needs an absolute device path such as /dev/ttyUSB0");
  }
  std::vector<std::string_view> allowed{"baud"};
  allowed.insert(allowed.end(), extra.begin(), extra.end());
  if (auto known = check_keys(parts, allowed); !known) return known.error();
  SerialUri s;
  s.path = parts.path;
  s.baud = default_baud;
  for (const auto& [key, value] : parts.options) {
    if (key != "baud") {
      s.options[key] = value;
      continue;
    }
    auto baud = parse_baud(value);
    if (!baud) return baud.error();
    s.baud = *baud;
  }
  return s;
}

Error uri_error(std::string_view uri, const Error& why, std::string_view forms) {
  return Error{why.kind, fmt::format("device \"{}\": {} (allowed: {})", printable(uri), printable(why.message), forms)};
}

}  // namespace armctl::transport

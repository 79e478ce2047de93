// The shape every device URI shares (`--device`, `--bus`, `--upstream`):
//   KIND[:PATH][?KEY=VALUE[&KEY=VALUE...]]     a bare absolute path is the serial kind
// and THE parser of serial ports, `serial:/dev/ttyUSB0[?baud=N]`. Which kinds exist and what
// their other options mean belongs to each device family (joint bus, Robot Commands, the
// arm controller's upstream); they all split and check options here, so the same text means
// the same thing everywhere and a mistake gets the same message.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace armctl::transport {

struct UriParts {
  std::string kind;  // "serial" for a bare absolute path
  std::string path;  // after "KIND:", up to '?' ("" if none)
  bool has_path = false;  // "KIND:" was written (or a bare path)
  bool has_query = false;  // a '?' was written
  std::map<std::string, std::string> options;
};

// Errors (invalid_argument) say what is wrong with the text ("option 'x' is not key=value",
// "option 'baud' given twice"); callers prefix the URI and add their accepted forms.
Result<UriParts> split_uri(std::string_view uri);

// Refuses any option not in `allowed`: "unknown option 'speed' (this device takes: baud, config)".
Status check_options(const UriParts& parts, std::initializer_list<std::string_view> allowed);

// A standard line rate ("baud 'x' is not a whole number", "baud 1234 is not a standard rate").
Result<std::uint32_t> parse_baud(std::string_view text);

struct SerialUri {
  std::string path;
  std::uint32_t baud = 9600;
  std::map<std::string, std::string> options;  // the `extra` options that were given
};

// A serial port: `serial:/dev/PATH[?baud=N]` or a bare absolute path. `extra` names the further
// options the caller's device takes (the joint bus: chip, select, dialect); anything else is
// refused.
Result<SerialUri> parse_serial_uri(const UriParts& parts, std::uint32_t default_baud,
                                   std::initializer_list<std::string_view> extra = {});

// Prefixes an error with the URI and appends the forms a device family accepts:
// `device "TEXT": WHY (allowed: FORMS)`.
Error uri_error(std::string_view uri, const Error& why, std::string_view forms);

}  // namespace armctl::transport

#include "protocol/robot_commands/hid_report.hpp"

#include <string>

namespace armctl::rc {

std::array<std::uint8_t, kHidWriteSize> encode_hid_report(const Frame& frame) {
  const auto bytes = encode_frame(frame);  // throws if too long for a report
  std::array<std::uint8_t, kHidWriteSize> report{};
  report[0] = 0x00;  // report ID
  for (std::size_t i = 0; i < bytes.size(); ++i) report[1 + i] = bytes[i];
  return report;
}

Result<Frame> decode_hid_report(std::span<const std::uint8_t> report) {
  std::size_t start = 0;
  // A leading report ID 0x00 is only taken as such when `55 55` follows it.
  if (report.size() >= 3 && report[0] == 0x00 && report[1] == kHeaderByte &&
      report[2] == kHeaderByte) {
    start = 1;
  }
  auto body = report.subspan(start);
  if (body.size() < 4 || body[0] != kHeaderByte || body[1] != kHeaderByte) {
    return Error{ErrorKind::protocol,
                 "HID report of " + std::to_string(report.size()) +
                     " bytes does not start with 55 55 (optionally after report ID 00)"};
  }
  const std::uint8_t len = body[2];
  if (len < kMinLen || len > kMaxLen) {
    return Error{ErrorKind::protocol, "HID report LEN " + std::to_string(len) +
                                          " is outside 2.." + std::to_string(kMaxLen)};
  }
  if (body.size() < 2u + len) {
    return Error{ErrorKind::protocol, "HID report LEN " + std::to_string(len) + " needs " +
                                          std::to_string(2u + len) + " bytes but the report has " +
                                          std::to_string(body.size())};
  }
  Frame f;
  f.cmd = body[3];
  f.data.assign(body.begin() + 4, body.begin() + 2 + len);
  return f;
}

}  // namespace armctl::rc

#include "protocol/robot_commands/frame.hpp"

#include <cstdio>

#include "core/error.hpp"

namespace armctl::rc {

std::vector<std::uint8_t> encode_frame(const Frame& frame) {
  if (frame.data.size() > kMaxData) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "Robot Commands frame DATA is " + std::to_string(frame.data.size()) +
                          " bytes; at most " + std::to_string(kMaxData) +
                          " fit one 64-byte report");
  }
  std::vector<std::uint8_t> out;
  out.reserve(4 + frame.data.size());
  out.push_back(kHeaderByte);
  out.push_back(kHeaderByte);
  out.push_back(static_cast<std::uint8_t>(frame.data.size() + 2));
  out.push_back(frame.cmd);
  out.insert(out.end(), frame.data.begin(), frame.data.end());
  return out;
}

std::string to_hex(const std::vector<std::uint8_t>& bytes) {
  std::string out;
  char buf[4];
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%02X", bytes[i]);
    if (i) out += ' ';
    out += buf;
  }
  return out;
}

}  // namespace armctl::rc

// One Robot Commands frame: `55 55 LEN CMD DATA`, LEN = len(DATA) + 2 (spec "Frame").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace armctl::rc {

constexpr std::uint8_t kHeaderByte = 0x55;
// A frame must fit one 64-byte HID report (spec "Links"): 2 header bytes + LEN bytes.
constexpr std::size_t kReportSize = 64;
constexpr std::uint8_t kMinLen = 2;
constexpr std::uint8_t kMaxLen = kReportSize - 2;
constexpr std::size_t kMaxData = kMaxLen - 2;

struct Frame {
  std::uint8_t cmd = 0;
  std::vector<std::uint8_t> data;
  bool operator==(const Frame&) const = default;
};

// Serial form of a frame. Throws ArmctlError(invalid_argument) if DATA exceeds kMaxData
// (typed encoders never produce such a frame).
std::vector<std::uint8_t> encode_frame(const Frame& frame);

// "55 55 04 0F 4C 1D": for logs, errors and tests.
std::string to_hex(const std::vector<std::uint8_t>& bytes);

}  // namespace armctl::rc

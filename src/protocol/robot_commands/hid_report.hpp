// USB HID framing (spec "Links"): one frame per 64-byte report, the rest is padding.
// hidapi writes take the report ID 0x00 first (65 bytes); reads return 64 bytes starting
// at `55 55`, or on some stacks a leading 0x00 first: both are accepted.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "core/error.hpp"
#include "protocol/robot_commands/frame.hpp"

namespace armctl::rc {

constexpr std::size_t kHidWriteSize = kReportSize + 1;

// Report ID 0x00 + the serial form of the frame + zero padding to 64 bytes.
// Throws ArmctlError(invalid_argument) if the frame cannot fit.
std::array<std::uint8_t, kHidWriteSize> encode_hid_report(const Frame& frame);

// The frame in an input report (with or without a leading 0x00), padding stripped by LEN.
// Errors (protocol) name what was wrong: no `55 55`, bad LEN, report shorter than LEN says.
Result<Frame> decode_hid_report(std::span<const std::uint8_t> report);

}  // namespace armctl::rc

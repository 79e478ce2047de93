// What the xArm board reads back over its servo bus when a read is answered by no servo, by
// one, or by several at once (two servos sharing an ID: core/miscalibration.hpp).
//
// A bus servo answers a read with a frame of the LX bus-servo protocol: 55 55 ID LEN CMD
// PARAMS... CHECKSUM, LEN = 3 + params, CHECKSUM = ~(ID + LEN + CMD + PARAMS) & 0xFF. Servos
// with the same ID answer together, after the same delay, on one half-duplex line that any
// transmitter pulls low: the board receives the bitwise AND of their frames. It keeps the
// result only if its checksum is right, which it is when the servos sent the same bytes
// (e.g. two servos standing at the same position) and by chance otherwise; then it decodes
// whatever the AND made of the parameters.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace armctl::xarm {

// LX bus-servo read commands the board issues.
inline constexpr std::uint8_t kServoPositionReadCmd = 28;  // params: position s16, little-endian
inline constexpr std::uint8_t kServoOffsetReadCmd = 19;    // params: offset s8

// The frame one servo sends.
std::vector<std::uint8_t> servo_reply_frame(std::uint8_t id, std::uint8_t cmd, std::span<const std::uint8_t> params);

// The parameters the board decodes when every entry of `answers` (each servo's parameters,
// all the same length) answers `cmd` for `id` at once; nothing when none answered or the
// collided frame's checksum is wrong.
std::optional<std::vector<std::uint8_t>> read_over_bus(std::uint8_t id, std::uint8_t cmd,
                                                       std::span<const std::vector<std::uint8_t>> answers);

}  // namespace armctl::xarm

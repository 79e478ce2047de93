// CRC-32 (IEEE 802.3, reflected, as zlib computes it): detects torn or corrupted state
// files. Not a security measure.
#pragma once

#include <cstdint>
#include <span>

namespace armctl::rc_board {

std::uint32_t crc32(std::span<const std::uint8_t> bytes);

}  // namespace armctl::rc_board

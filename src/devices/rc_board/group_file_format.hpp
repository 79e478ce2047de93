// On-disk form of one stored action group (state dir, "group-NNN.grp"):
//
//   "ARMGRP1\n"                       8 bytes magic and format version
//   group u8, servo_count u8, action_count u16le
//   action_count x { milliseconds u16le, servo_count x { servo u8, position u16le } }
//   crc32 u32le                       over every byte before it
//
// Decoding checks everything (magic, exact length, CRC, counts, ranges), so a torn or
// foreign file is never mistaken for a group.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "devices/rc_board/action_group.hpp"

namespace armctl::rc_board {

// The largest file encode_group_file() writes (1,020 actions of 255 servos): loaders read
// no more than this, so a huge or sparse file in the state dir is refused unread.
inline constexpr std::size_t kMaxGroupFileBytes = 8 + 4 + 1020 * (2 + 3 * 255) + 4;

std::vector<std::uint8_t> encode_group_file(GroupNumber group, const ActionGroup& actions);
// `expected_group`: the number the file name claims (a mismatch is corruption).
Result<ActionGroup> decode_group_file(std::span<const std::uint8_t> bytes,
                                      GroupNumber expected_group);

}  // namespace armctl::rc_board

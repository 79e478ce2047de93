// Action files of the xArm maker's PC software (".rob"), converted to and from our group
// files (files/action_group_file.hpp). The maker does not document the layout; what is
// known and what is guessed is in docs/teach.md ".rob files". As armctl reads it:
//
//   offset 0   6 bytes  "SOBARM"                      (checked)
//   offset 6   uint16   frame count, 1..1020          (checked against the file size)
//   offset 8   8 bytes  unknown; not read on import, zeros on export
//   offset 16  frames of 14 bytes: uint16 time in ms (0..30000), then six uint16 servo
//              positions (0..1000) for servos 1..6 in that order
//
// Every 16-bit field little-endian (guessed: the software runs on x86 Windows and the
// board's own protocol is little-endian). A file that does not fit is refused with what
// was found at which offset; nothing is returned on error.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "files/action_group_file.hpp"

namespace armctl::files {

inline constexpr std::size_t kRobHeaderBytes = 16;
inline constexpr std::size_t kRobFrameBytes = 14;
inline constexpr std::size_t kRobServos = 6;
inline constexpr std::size_t kRobMaxFrames = kGroupFileMaxActions;
inline constexpr std::size_t kRobMaxBytes = kRobHeaderBytes + kRobMaxFrames * kRobFrameBytes;

// A group of servos 1..6 with every position given. `source` names the file in errors
// ("wave.rob: offset 6: ...").
Result<ActionGroupFile> parse_rob_file(const std::vector<std::uint8_t>& bytes,
                                       std::string_view source = "<rob>");
// Reads a regular file of at most kRobMaxBytes, then parses it.
Result<ActionGroupFile> read_rob_file(const std::filesystem::path& path);

// The .rob bytes of `group`; refused (invalid_argument, saying why) unless its servos are
// exactly 1..6 (any order: frames list them 1..6) and every position is given (the layout
// has no "keep").
Result<std::vector<std::uint8_t>> format_rob_file(const ActionGroupFile& group);

}  // namespace armctl::files

// Action-group files: a text format people write by hand, for `armctl xarm group download`
// (format reference with an example: docs/action-groups.md).
//
//   # wave: three servos, four actions
//   servos 3                       optional header: how many servos every action names
//   1000  1=500 2=300 3=700        time in ms (0..30000, "ms" suffix allowed), then
//   800   1=30deg 2=-15deg 3=500   servo=position: 0..1000, degrees from centre
//   500   1=keep 2=500 3=500       (-120..120, "30deg", "-12.5deg"), or keep (0xFF00:
//   0     1=500 2=500 3=500        the servo stays where it is)
//
// '#' starts a comment; blank lines are ignored. 1..1,020 actions. Every action names the
// same servos (GroupDownload sub 2 fixes one servo count per group), each once, 1..17 of
// them (what one sub-4 frame can carry); servo IDs 1..254 (the board decides which exist).
// Errors name the line, the field and what is allowed; nothing is returned on error.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::files {

inline constexpr std::size_t kGroupFileMaxActions = rc::kActionsMax;
inline constexpr std::size_t kGroupFileMaxServos = 17;

struct ActionGroupFile {
  std::vector<std::uint8_t> servos;  // the servo set, in the order of the first action
  std::vector<rc::GroupAction> actions;
  bool operator==(const ActionGroupFile&) const = default;
};

// `source` names the text in errors ("wave.grp:12: ...").
Result<ActionGroupFile> parse_action_group(std::string_view text,
                                           std::string_view source = "<group>");
Result<ActionGroupFile> read_action_group_file(const std::filesystem::path& path);

// Canonical text: header, one action per line, positions as numbers or keep.
// parse_action_group(format_action_group(g)) == g for any valid g.
std::string format_action_group(const ActionGroupFile& group);

}  // namespace armctl::files

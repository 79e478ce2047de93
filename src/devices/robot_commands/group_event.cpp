#include "devices/robot_commands/group_event.hpp"

#include <fmt/core.h>

namespace armctl::robot_commands {

std::string describe(const GroupEvent& e) {
  std::string out = e.group ? fmt::format("group {} {}", *e.group, to_string(e.kind))
                            : fmt::format("group {}", to_string(e.kind));
  if (e.count) out += *e.count == 0 ? " (continuous)" : fmt::format(" ({} times)", *e.count);
  if (e.variant) out += " [board variant without group/count]";
  return out;
}

}  // namespace armctl::robot_commands

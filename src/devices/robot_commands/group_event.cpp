#include "devices/robot_commands/group_event.hpp"

#include <fmt/core.h>

namespace armctl::robot_commands {

const char* to_string(GroupEventKind kind) {
  switch (kind) {
    case GroupEventKind::started: return "started";
    case GroupEventKind::stopped: return "stopped";
    case GroupEventKind::finished: return "finished";
  }
  return "unknown";
}

std::string describe(const GroupEvent& e) {
  std::string out = e.group ? fmt::format("group {} {}", *e.group, to_string(e.kind))
                            : fmt::format("group {}", to_string(e.kind));
  if (e.count) out += *e.count == 0 ? " (continuous)" : fmt::format(" ({} times)", *e.count);
  if (e.variant) out += " [board variant without group/count]";
  return out;
}

}  // namespace armctl::robot_commands

#include "arm/action_groups.hpp"

#include "devices/robot_commands/group_start.hpp"

namespace armctl::arm {

Status RcActionGroups::run_started(std::uint8_t group, std::uint16_t times) {
  return robot_commands::run_group_started(client_, group, times);
}

}  // namespace armctl::arm

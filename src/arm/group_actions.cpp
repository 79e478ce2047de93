#include "arm/group_actions.hpp"

#include <cmath>

#include <fmt/core.h>

#include "protocol/robot_commands/messages.hpp"

namespace armctl::arm {

Result<robot_commands::GroupAction> servo_action(const ArmModel& model, const std::vector<std::optional<double>>& targets,
                                                 std::uint16_t time_ms) {
  constexpr Protocol kRc = Protocol::robot_commands;
  if (targets.size() != model.joints.size())
    return Error{ErrorKind::invalid_argument,
                 fmt::format("{} targets given for arm '{}' with {} joints", targets.size(), model.name, model.joints.size())};
  std::vector<double> q(model.joints.size(), 0.0);
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (!targets[i]) continue;
    if (!model.joints[i].map(kRc))
      return Error{ErrorKind::unsupported,
                   fmt::format("joint {} of arm '{}' has no Robot Commands servo: only a Robot Commands board replays "
                               "action groups",
                               model.joints[i].name, model.name)};
    q[i] = *targets[i];
  }
  robot_commands::GroupAction action;
  action.time_ms = time_ms;
  if (!model.supports(kRc)) return action;  // no target given: nothing to convert
  const std::vector<double> device = model.to_device(kRc, q);
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (!targets[i]) continue;
    const JointModel& j = model.joints[i];
    const double units = std::round(device[i]);
    if (!(units >= 0 && units <= rc::kPositionMax))
      return Error{ErrorKind::invalid_argument,
                   fmt::format("joint {}: {} is servo position {:.0f}, outside the servo's 0..{}", j.name,
                               format_quantity(j.dimension, q[i]), units, rc::kPositionMax)};
    action.targets.push_back({std::uint8_t(j.map(kRc)->id), std::uint16_t(units)});
  }
  return action;
}

}  // namespace armctl::arm

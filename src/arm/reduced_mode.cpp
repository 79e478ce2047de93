#include "arm/reduced_mode.hpp"

#include <fmt/core.h>

#include "core/quantity.hpp"

namespace armctl::arm {

Result<ReducedLimits> reduced_limits(const ArmModel& model, const scene::ReducedMode& mode) {
  ReducedLimits out;
  out.tool_speed = mode.tool_speed;
  for (const scene::ReducedJointRange& r : mode.joints) {
    const std::string key = "reduced.joints." + r.joint;
    std::size_t index = model.joints.size();
    std::string names;
    for (std::size_t i = 0; i < model.joints.size(); ++i) {
      if (model.joints[i].name == r.joint) index = i;
      names += (names.empty() ? "" : ", ") + model.joints[i].name;
    }
    if (index == model.joints.size())
      return Error{ErrorKind::invalid_config,
                   fmt::format("{}: arm '{}' has no joint '{}' (its joints: {})", key, model.name, r.joint, names)};
    const JointModel& j = model.joints[index];
    const double lower = from_display(j.dimension, r.lower), upper = from_display(j.dimension, r.upper);
    // A hair of rounding (degrees written with three decimals) is not a range outside.
    constexpr double kSlack = 1e-9;
    if (lower < j.limits.lower - kSlack || upper > j.limits.upper + kSlack)
      return Error{ErrorKind::invalid_config,
                   fmt::format("{}: [{:g}, {:g}] {} is not inside joint {}'s own limits {}..{}: a reduced range narrows "
                               "them",
                               key, r.lower, r.upper, display_unit(j.dimension), j.name,
                               format_quantity(j.dimension, j.limits.lower), format_quantity(j.dimension, j.limits.upper))};
    out.joint_ranges.push_back(scene::JointRange{
        index, lower, upper, fmt::format("joint '{}'", j.name),
        fmt::format("its reduced range {}..{}", format_quantity(j.dimension, lower), format_quantity(j.dimension, upper))});
  }
  return out;
}

}  // namespace armctl::arm

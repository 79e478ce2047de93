// Reduced mode of a scene for one arm (docs/scene.md "Fence and reduced mode"): its joint
// ranges in SI, each checked to lie inside the joint's own limits, and its cap on the tool's
// speed. What the arm's kinematics checks plans against while the mode is on.
#pragma once

#include <optional>
#include <vector>

#include "arm/arm_model.hpp"
#include "core/error.hpp"
#include "scene/collision_world.hpp"
#include "scene/scene_limits.hpp"

namespace armctl::arm {

struct ReducedLimits {
  std::optional<double> tool_speed;            // m/s of the tool point
  std::vector<scene::JointRange> joint_ranges;  // SI
};

// `mode` as the scene file gave it (degrees, millimetres for a prismatic joint). Errors
// (invalid_config): a joint the arm does not have, a range outside the joint's own limits,
// each naming the key ("reduced.joints.servo1"), the value and what is allowed.
Result<ReducedLimits> reduced_limits(const ArmModel& model, const scene::ReducedMode& mode);

}  // namespace armctl::arm

// Whether an arm's URDF gives any link a <collision> shape. Without one nothing can be checked
// against the arm's body: the arm file's fence and reduced mode are refused, and so is a scene.
#pragma once

#include "arm/arm_model.hpp"

namespace armctl::arm {

bool has_collision_shapes(const ArmModel& model);

}  // namespace armctl::arm

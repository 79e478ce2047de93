// The xArm family: a base yaw joint, three pitch joints about parallel horizontal axes and a
// wrist roll joint about the approach direction, the tool point on the roll axis in the
// plane of the pitch joints through the base axis. Five joints: position plus tool pitch
// and roll; the tool's yaw follows from the position (the base faces the point, or turns
// half a turn and reaches back over the top). Elbow up or down in each case.
#pragma once

#include <memory>
#include <span>

#include "motion/kinematics.hpp"

namespace armctl::motion {

Result<std::unique_ptr<Kinematics>> make_xarm_kinematics(const UrdfChain& chain,
                                                         std::span<const PositionLimits> limits);

}  // namespace armctl::motion

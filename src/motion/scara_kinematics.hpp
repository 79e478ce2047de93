// The SCARA family: a prismatic column (Z), three revolute joints about axes parallel to it
// (SHOULDER, UAE, UAJ) and a spherical wrist (UAJ, SKE, SKF meet in the wrist centre).
// Analytic IK: the wrist centre fixes Z and the planar shoulder/elbow pair (elbow left or
// right); the wrist's three axes then give two solutions (wrist flipped or not).
#pragma once

#include <memory>
#include <span>

#include "motion/kinematics.hpp"

namespace armctl::motion {

Result<std::unique_ptr<Kinematics>> make_scara_kinematics(const UrdfChain& chain,
                                                          std::span<const PositionLimits> limits);

}  // namespace armctl::motion

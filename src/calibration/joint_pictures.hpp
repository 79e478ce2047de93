// The pictures the calibration wizard's direction and zero steps refer to (docs/calibration.md
// "Pictures", docs/images/joints-xarm.svg and joints-scara.svg): one panel per joint, the arm
// drawn from its collision shapes with every joint at its mark (grey: how the arm stands when
// the joint is at its mark) and, in blue, with that joint moved a little in its positive
// direction, an arrow showing the way. A revolute joint is seen along its axis, from the
// side the axis points to, so its positive turn is the picture's counter-clockwise (the
// right-hand rule); a prismatic joint is seen from the side, its travel in the picture.
// Pure: the arm model in, SVG text out; drawn from the arm file, so an arm file of one's own
// gets its own pictures (`armctl calibrate --pictures FILE`).
#pragma once

#include <string>

#include "arm/arm_model.hpp"
#include "core/error.hpp"

namespace armctl::calibration {

// How far the blue arm is moved: enough to see the way, small enough to stay near the mark.
inline constexpr double kPictureTurn = 0.4363323129985824;  // rad (25 deg)
inline constexpr double kPictureTravel = 0.030;             // m

// Refused (invalid_config) when the model has no link bodies (no URDF shapes) or a joint
// moves no body.
Result<std::string> joint_pictures_svg(const arm::ArmModel& model);

}  // namespace armctl::calibration

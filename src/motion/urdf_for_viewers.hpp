// The URDF text an arm is drawn from, for viewers that read a URDF themselves (the
// dashboard's 3D view, ROS's robot_description for rviz): the file as written, with the arm
// file's calibrated link lengths written into those joints' <origin xyz>, so that they draw
// the arm the kinematics and the collision checks use, not the shipped one; and each
// <capsule> (which viewers do not know: motion/urdf_capsules.hpp) as a cylinder with a sphere
// on each end, in as many elements. Pure: text in, text or error out.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "motion/urdf_chain.hpp"

namespace armctl::motion {

// `urdf_xml` with every joint named in `lengths` given that offset length, its direction kept
// (apply_origin_lengths: the same numbers the chain and the link bodies are read with), and
// its capsules drawn as above. Everything else — visuals, comments, elements urdfdom does not
// know — stays as written. With no lengths and no capsules, the text unchanged. Errors
// (invalid_config) as read_urdf_chain's and apply_origin_lengths'.
Result<std::string> urdf_for_viewers(std::string_view urdf_xml, std::span<const OriginLength> lengths);

}  // namespace armctl::motion

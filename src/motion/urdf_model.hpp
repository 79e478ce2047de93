// urdfdom's whole-document parse behind the guards every URDF reader needs (UTF-8 text, no
// '%' that urdfdom's logger would take for a printf format, urdfdom's complaints collected
// into the error instead of stderr), for the readers of one part of a URDF: the kinematic
// chain (motion/urdf_chain.hpp) and the links' collision shapes (motion/link_bodies.hpp).
#pragma once

#include <string>

#include <Eigen/Geometry>
#include <urdf_world/types.h>
#include <urdf_model/model.h>

#include "core/error.hpp"

namespace armctl::motion {

// The parsed document, or invalid_config saying what urdfdom (or the guards) refused.
Result<urdf::ModelInterfaceSharedPtr> parse_urdf_model(const std::string& xml);

// An <origin> as a transform; invalid_config naming `what` ("joint 'servo6'") when it is
// not finite or not a rotation.
Result<Eigen::Isometry3d> urdf_pose(const urdf::Pose& pose, const std::string& what);

}  // namespace armctl::motion

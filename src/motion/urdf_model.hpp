// urdfdom's whole-document parse behind the guards every URDF reader needs (UTF-8 text, no
// '%' that urdfdom's logger would take for a printf format, urdfdom's complaints collected
// into the error instead of stderr), for the readers of one part of a URDF: the kinematic
// chain (motion/urdf_chain.hpp) and the links' collision shapes (motion/link_bodies.hpp).
#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <urdf_world/types.h>
#include <urdf_model/model.h>

#include "core/error.hpp"
#include "motion/urdf_capsules.hpp"
#include "motion/urdf_chain.hpp"

namespace armctl::motion {

// The parsed document, or invalid_config saying what urdfdom (or the guards) refused. Its
// <capsule> shapes, which urdfdom does not know, reach it as cylinders of their size; where
// they were goes to `capsules` when given (motion/urdf_capsules.hpp).
Result<urdf::ModelInterfaceSharedPtr> parse_urdf_model(const std::string& xml,
                                                        std::vector<UrdfCapsule>* capsules = nullptr);

// Every joint named in `lengths` gets its <origin> offset scaled to that length, the
// direction kept. Refused (invalid_config, naming the joint): a joint the URDF does not have,
// named twice, whose origin has no offset (no direction to keep), or a length that is not
// finite and above zero.
Status apply_origin_lengths(urdf::ModelInterface& model, std::span<const OriginLength> lengths);

// An <origin> as a transform; invalid_config naming `what` ("joint 'servo6'") when it is
// not finite or not a rotation.
Result<Eigen::Isometry3d> urdf_pose(const urdf::Pose& pose, const std::string& what);

}  // namespace armctl::motion

// Capsules in a URDF. URDF knows boxes, cylinders, spheres and meshes; a capsule — a cylinder
// with a half sphere on each end, the shape that fits a robot's links best and the one FCL and
// MuJoCo check fastest — is not in it, and urdfdom refuses a document with one. armctl reads
// <capsule radius="R" length="L"/> in a link's <collision> (or <visual>) <geometry>: R and L in
// metres, L the straight part's length along z between the two half spheres' centres (FCL's
// Capsule, three.js's CapsuleGeometry). urdfdom gets it as a cylinder of that size; the link
// bodies know it is a capsule (motion/link_bodies.hpp), and viewers, which do not know
// capsules either, get a cylinder and two spheres (motion/urdf_for_viewers.hpp). Pure.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace armctl::motion {

struct UrdfCapsule {
  std::string link;
  std::size_t collision = 0;  // which of the link's <collision> elements, from 0 in document order
  double radius = 0, length = 0;  // m
};

struct UrdfWithoutCapsules {
  std::string xml;  // every <capsule> a <cylinder> of its radius and length
  std::vector<UrdfCapsule> capsules;  // the <collision> ones (visuals only change shape)
};

// `xml` (well-formed UTF-8 text: the caller's guards have run) as urdfdom can read it, and
// where its collision capsules were. Text without "<capsule" is returned as it is. Errors
// (invalid_config): a capsule whose radius or length is missing or not a number above 0,
// naming the link and the element.
Result<UrdfWithoutCapsules> without_capsules(const std::string& xml);

}  // namespace armctl::motion

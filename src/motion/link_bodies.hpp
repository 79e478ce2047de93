// Every link of an arm as a rigid body with its collision shapes: the URDF's tree below the
// base link (chain joints, the gripper, fixed links), each link's <collision> primitives, and
// forward kinematics of all of them at once. What a collision check needs from the URDF and
// nothing else. Pure: URDF text in, a value out; poses from joint values.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "core/error.hpp"
#include "motion/urdf_chain.hpp"

namespace armctl::motion {

// A convex primitive centred on its frame, as URDF and FCL define them: a box's edge
// lengths, a cylinder's radius and length along its z axis, a sphere's radius (m); a capsule
// (FCL's, MuJoCo's; URDF has none: motion/urdf_capsules.hpp) is a cylinder of `length` along z
// with a half sphere of its radius on each end, so `length` + 2 radius long in all.
struct Shape {
  enum class Kind { box, cylinder, sphere, capsule };
  Kind kind = Kind::box;
  // box: x y z; cylinder and capsule: radius, length, 0; sphere: radius, 0, 0
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // in its body's frame
};
const char* to_string(Shape::Kind kind);  // "box", "cylinder", "sphere", "capsule"

// Half the widest extent of `shape` about its own centre (m): every point of it lies within.
double bounding_radius(const Shape& shape);
// The shape's axis-aligned bounding box when its frame is `pose` (min, max corners).
void world_bounds(const Shape& shape, const Eigen::Isometry3d& pose, Eigen::Vector3d& low, Eigen::Vector3d& high);

struct LinkBody {
  std::string name;
  int parent = -1;  // the body it hangs from (index), -1 for the base link
  // Parent body's frame to this body's frame with its joint at zero (every fixed joint
  // between two moving ones folded in: bodies are links, one each).
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, in this body's frame
  bool prismatic = false;
  int joint = -1;  // which joint value moves it (the arm's joint order); -1: fixed to its parent
  std::vector<Shape> shapes;  // its <collision> elements
};

struct LinkBodies {
  std::vector<LinkBody> bodies;  // the base link first; every parent before its children

  // Index of the link named `name`, or nothing.
  std::optional<int> find(std::string_view name) const;
  // Every body's frame in the base frame at `joints` (one value per joint of the arm, SI).
  void poses(std::span<const double> joints, std::vector<Eigen::Isometry3d>& out) const;
  // Whether a body moves with some joint (a fixed link of the base never does).
  bool moves(int body) const;
  // Whether joint `joint` moves body `body` (it lies between the base and the body).
  bool moved_by(int body, int joint) const;
};

// The links below `base_link` of the URDF, their <collision> shapes, and which of
// `joint_names` (the arm's joints, in order) moves each. Errors (invalid_config) name the
// link or joint: a <collision> mesh (primitives only), a size that is not finite and
// positive, a moving joint the arm does not name, a joint type other than revolute,
// continuous, prismatic or fixed. `lengths`: origin offsets to replace, as read_urdf_chain's.
Result<LinkBodies> read_link_bodies(std::string_view urdf_xml, std::string_view base_link,
                                    std::span<const std::string> joint_names,
                                    std::span<const OriginLength> lengths = {});

}  // namespace armctl::motion

// The moving joints of one chain of a URDF robot description, base to tip, as plain values:
// what the kinematics needs from the URDF and nothing else (no meshes, no inertia).
// Parsing is pure (text in, value or error out); read_urdf_chain_file only adds the file.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "core/error.hpp"

namespace armctl::motion {

enum class ChainJointType { revolute, prismatic };
const char* to_string(ChainJointType type);  // "revolute", "prismatic"

// The URDF <limit> element of a joint (rad or m; rad/s or m/s; N m or N).
struct UrdfJointLimits {
  double lower = 0, upper = 0, velocity = 0, effort = 0;
};

struct ChainJoint {
  std::string name;
  ChainJointType type = ChainJointType::revolute;
  // The joint's <origin> element as written: parent link frame to joint frame at zero.
  Eigen::Vector3d origin_xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3d origin_rpy = Eigen::Vector3d::Zero();  // R = Rz(y) Ry(p) Rx(r)
  // Unit axis in the joint frame: turned about (revolute) or slid along (prismatic).
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  UrdfJointLimits limits;
  // From the previous moving joint's frame (after its motion; the base link's frame for
  // the first joint) to this joint's frame at zero: every fixed joint between them, then
  // this joint's origin.
  Eigen::Isometry3d from_previous = Eigen::Isometry3d::Identity();
};

// A fixed joint of the chain (the tool point): its <origin> as written, and which moving
// joint comes after it (joints.size(): none, it is between the last one and the tip).
struct FixedChainJoint {
  std::string name;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  std::size_t before = 0;
};

// A calibrated length: the URDF joint `joint`'s <origin> offset made `length` long (m), its
// direction kept (the arm file's "link_lengths", docs/calibration.md). Applied to the parsed
// URDF before the chain and the link bodies are read from it, so both see the same arm.
struct OriginLength {
  std::string joint;
  double length = 0;
};

struct UrdfChain {
  std::string robot_name;
  std::string base_link, tip_link;
  std::vector<ChainJoint> joints;  // the moving joints, base to tip
  // From the last moving joint's frame (after its motion) to the tip link's frame: the
  // fixed joints after it (the whole chain when there is no moving joint).
  Eigen::Isometry3d tip_from_last = Eigen::Isometry3d::Identity();
  // Names of the fixed joints along the chain, base to tip (for messages and docs).
  std::vector<std::string> fixed_joints;
  // The same fixed joints with their origins and places, for code that re-folds the chain
  // with other lengths (src/calibration).
  std::vector<FixedChainJoint> fixed;
};

// The chain from base_link to tip_link of the URDF text. Errors (invalid_config) name the
// URDF element and what is allowed: not URDF (or not UTF-8 text), a missing link, a tip not below the base,
// joint types other than revolute, prismatic and fixed along the chain, a zero axis,
// limits that are missing, not finite or empty, mimic joints in the chain. `lengths`: origin
// offsets to replace (apply_origin_lengths).
Result<UrdfChain> read_urdf_chain(std::string_view urdf_xml, std::string_view base_link,
                                  std::string_view tip_link, std::span<const OriginLength> lengths = {});

// The same from a file; errors name the file.
Result<UrdfChain> read_urdf_chain_file(const std::string& path, std::string_view base_link,
                                       std::string_view tip_link);

}  // namespace armctl::motion

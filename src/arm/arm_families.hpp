// The kinematic families an arm file can name ("family": "xarm", "scara", or one added with
// register_arm_family): how to build the chain's kinematics from the URDF chain, and the
// family's rules that the Arm API's kinematics (arm/arm_kinematics.hpp) applies so that no
// caller tests which family an arm is. An open table (core/named_registry.hpp): a new arm adds
// its family from its own files (docs/architecture.md "How to add an arm").
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "motion/kinematics.hpp"

namespace armctl::arm {

// What sets a family's tool orientation apart, for the planner and the Arm API.
struct FamilyRules {
  // The tool's yaw is where the arm points: a goal's empty yaw follows its position, and
  // roll/pitch/yaw are read in the form whose yaw is that direction (the 5-joint xArm).
  bool yaw_follows_position = false;
  // A target without a pitch leaves the tool's pitch free (the middle of the widest run of
  // pitches that reach).
  bool pitch_free = false;
  // The chain reaches positions with the nearest orientation (fewer than 6 joints).
  bool reaches_nearest_orientation = false;
};

struct ArmFamily {
  std::string name;  // the arm file's "family"
  // The chain's kinematics (one limit per chain joint, base to tool), or invalid_config
  // when the chain does not have the family's shape.
  std::function<Result<std::unique_ptr<motion::Kinematics>>(const motion::UrdfChain&,
                                                            std::span<const motion::PositionLimits>)>
      make;
  FamilyRules rules;
};

// Adds a family (invalid_argument if its name is taken or it has no `make`). The built-in
// ones (xarm, scara) are there from the start.
Status register_arm_family(ArmFamily family);
// The family named `name`, or invalid_argument "unknown arm family 'x' (known: xarm, scara)".
// The pointer stays valid for the life of the program.
Result<const ArmFamily*> find_arm_family(std::string_view name);

}  // namespace armctl::arm

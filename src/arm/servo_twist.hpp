// From a tool twist to the chain joints' velocities, for the servo mode (arm/run_servo.hpp):
// the tool point's linear velocity first, its rotation as far as the joints left over allow
// (task priority, each by damped least squares with the damping growing as a singular value
// falls toward zero: near a singularity the velocities stay bounded instead of growing
// without limit, and a rotation the arm can hardly make gives way rather than flipping a
// joint through its stretched position). On the 5-joint xArm a rotation about the base's
// vertical is reached only through the wrist's roll when the tool points down; the rest of
// what cannot be reached is left out, never traded against the position.
#pragma once

#include <Eigen/Core>

#include "arm/arm_kinematics.hpp"
#include "motion/kinematics.hpp"

namespace armctl::arm {

// The tool point's geometric Jacobian in the base frame (rows vx vy vz wx wy wz; the arm
// file's tool frame applied), at `chain`.
motion::Jacobian tool_jacobian(const ArmKinematics& kinematics, const motion::JointVector& chain);

// How near the tool point's position is to a singularity: the ratio of the largest to the
// smallest singular value of the Jacobian's position rows (1 far from any, growing without
// bound at one). The rotation is left out: the 5-joint xArm cannot turn its tool every way
// anywhere, and the rotation gives way first (joint_velocities_for).
double position_condition(const motion::Jacobian& jacobian);

// The chain joints' velocities (rad/s or m/s) that move the tool point at `linear` (m/s) and
// turn the tool at `angular` (rad/s), both in the base frame, at `chain`.
motion::JointVector joint_velocities_for(const motion::Jacobian& jacobian, const Eigen::Vector3d& linear,
                                         const Eigen::Vector3d& angular);

}  // namespace armctl::arm

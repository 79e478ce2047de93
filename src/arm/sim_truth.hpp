// What the physical arm of a mis-assembled simulator (`sim?miscal=SEED`, core/miscalibration.hpp)
// is doing, in SI: the user's eyes, for tests that answer the calibration wizard as a user
// would ("which joint moved", "did it go the positive way", "the tool now touches P") and
// check what it recovered.
//
// The truth is the shipped arm file (its device mappings are how a well-built arm maps)
// with the URDF's link lengths corrected by the miscalibration's length errors. Pure: the
// caller reads the true device positions off the simulator (joint_sim::SimArm::true_position,
// xarm::XarmServos::true_position or xarm::EmulatorRunner::with_servos), so the arm layer
// links no simulator.
#pragma once

#include <span>
#include <vector>

#include "arm/arm_model.hpp"
#include "arm/protocols.hpp"
#include "core/error.hpp"
#include "core/miscalibration.hpp"
#include "motion/kinematics.hpp"

namespace armctl::arm {

class SimTruth {
 public:
  // `shipped`: the model of the shipped arm file (config/xarm.arm.json, config/scara.arm.json),
  // `protocol`: the one the simulator speaks (robot_commands for the xArm, joint_bus for the
  // SCARA's joints). Errors (invalid_argument): a length error on a joint the arm's URDF chain
  // does not have, a joint the model cannot map for that protocol.
  static Result<SimTruth> make(ArmModel shipped, Protocol protocol, Miscalibration miscal);

  const ArmModel& model() const { return model_; }
  const Miscalibration& miscalibration() const { return miscal_; }
  // The URDF chain with the length errors applied: the true geometry.
  const motion::UrdfChain& true_chain() const { return chain_; }

  // Every joint's true value (SI, the model's order: chain then gripper) from the true
  // device positions by device ID (entry id - 1: servo ID, joint number), couplings applied.
  std::vector<double> joints(std::span<const double> true_device_by_id) const;
  // The true tool pose (the arm file's tool frame on the true geometry) at true joint values.
  motion::Pose tool_pose(const std::vector<double>& true_joints) const;
  Eigen::Vector3d tool_position(const std::vector<double>& true_joints) const {
    return tool_pose(true_joints).position;
  }
  // The true device positions (by device ID) at true joint values: what a test hands to
  // SimArm::move_by_hand_to / XarmServos::move_by_hand_to to put the physical arm there (e.g.
  // the tool on a point: tool_position(true_joints)).
  std::vector<double> true_device_positions(const std::vector<double>& true_joints) const;
  // The device positions (by device ID) a mis-assembled arm reads where the physical arm
  // stands at these true joint values: what a calibrated arm file must map them to.
  std::vector<double> device_positions(const std::vector<double>& true_joints) const;

 private:
  SimTruth(ArmModel model, Protocol protocol, Miscalibration miscal, motion::UrdfChain chain)
      : model_(std::move(model)), protocol_(protocol), miscal_(std::move(miscal)), chain_(std::move(chain)) {}

  ArmModel model_;
  Protocol protocol_;
  Miscalibration miscal_;
  motion::UrdfChain chain_;
};

// `chain` with each link error of `miscal` applied: the joint's <origin> `error_mm` longer
// along its own direction. Errors (invalid_argument) name a joint the chain does not have
// (or whose origin has no length to lengthen).
Result<motion::UrdfChain> apply_link_errors(motion::UrdfChain chain, const Miscalibration& miscal);

// Forward kinematics of a URDF chain (base link to tip link frame) at chain joint values.
Eigen::Isometry3d chain_forward(const motion::UrdfChain& chain, std::span<const double> chain_joints);

}  // namespace armctl::arm

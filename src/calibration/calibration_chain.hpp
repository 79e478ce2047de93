// The arm's chain as the kinematic fit sees it: the tool point as a function of the joints'
// readings and of calibration parameters, the joints' zeros and the lengths of URDF joint
// origins (docs/calibration.md "The model"). Pure code, values in and out.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "arm/arm_model.hpp"
#include "core/error.hpp"
#include "motion/urdf_chain.hpp"

namespace armctl::calibration {

// One calibration parameter. Its value is a correction: for a zero, what is added to the
// joint's reading to give its true value (rad or m); for a length, what is added to the
// origin offset's length (m).
enum class ParameterKind { zero, length };
struct Parameter {
  ParameterKind kind = ParameterKind::zero;
  int joint = -1;      // zero: the chain joint's index (the model's order)
  std::string origin;  // length: the URDF joint whose <origin> offset it is
  std::string name;    // for people: "zero of servo4", "length of servo4's origin"
  bool operator==(const Parameter& o) const { return kind == o.kind && joint == o.joint && origin == o.origin; }
};
Parameter zero_parameter(const arm::ArmModel& model, int joint);
Parameter length_parameter(std::string origin);

class CalibrationChain {
 public:
  // From the arm's chain (with the arm file's link lengths applied) and its tool frame.
  static Result<CalibrationChain> make(const arm::ArmModel& model);

  int joint_count() const { return joint_count_; }
  // Every parameter this chain has, in the fit's order of preference: the revolute joints'
  // zeros base to tool, the origin lengths tool to base (of lengths that cannot be told
  // apart, the one nearest the tool is kept: it is the tool's own, the likeliest to differ),
  // then the prismatic joints' zeros (a slide's zero moves the tool as the length of an
  // origin along it does: the length is kept, so the joint's readings and limits stay as
  // its zero step left them, and a joint whose zero is at the end of its travel, as the
  // SCARA's Z, keeps it there).
  const std::vector<Parameter>& candidates() const { return candidates_; }
  // The current length of an origin offset (m); -1 when `origin` names none of the chain's.
  double length(const std::string& origin) const;

  // The tool point (base frame, m) at chain joint readings `q` with corrections `values`
  // (one per parameter of `parameters`, each a candidate of this chain).
  Eigen::Vector3d tool_point(const Eigen::VectorXd& q, const std::vector<Parameter>& parameters,
                             const Eigen::VectorXd& values) const;

 private:
  // The chain as a product of segments: a fixed transform (a URDF origin), then, unless the
  // origin is a fixed joint's, the joint's motion.
  struct Segment {
    std::string origin;  // the URDF joint whose origin this is
    Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // unit offset direction; zero: no offset
    int joint = -1;                                       // the moving joint after it; -1: fixed
    bool revolute = true;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  };
  std::vector<Segment> segments_;
  std::vector<Parameter> candidates_;
  Eigen::Vector3d tool_ = Eigen::Vector3d::Zero();  // the tool point in the tool link
  int joint_count_ = 0;
};

}  // namespace armctl::calibration

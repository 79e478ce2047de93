// Kinematics of an arm's chain: forward kinematics, analytic inverse kinematics (every
// solution), the Jacobian and its singularities. Pure code: value types in and out, no I/O,
// no allocation per solve. SI units throughout (metres, radians).
//
// The chain is the arm's motion joints in base-to-tool order (the gripper is not part of
// it): SCARA joints 1..6 (Z, SHOULDER, UAE, UAJ, SKE, SKF), xArm servos 6..2 (base yaw,
// shoulder, elbow, wrist pitch, wrist roll). Geometry comes from the arm's URDF
// (urdf_chain.hpp); each kinematic family checks that the chain has its shape.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "core/error.hpp"
#include "motion/urdf_chain.hpp"

namespace armctl::motion {

inline constexpr int kMaxChainJoints = 7;

// Joint positions of a chain (rad or m), at most kMaxChainJoints, never on the heap.
using JointVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxChainJoints, 1>;
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxChainJoints>;

// The tool frame in the base frame.
struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

// Fixed-axis roll (about x), pitch (about y), yaw (about z): R = Rz(yaw) Ry(pitch) Rx(roll).
struct Rpy {
  double roll = 0, pitch = 0, yaw = 0;
};
Eigen::Quaterniond from_rpy(const Rpy& rpy);
Rpy to_rpy(const Eigen::Quaterniond& q);

// Position limits of one chain joint (rad or m), used to keep IK solutions inside them.
struct PositionLimits {
  double lower = 0, upper = 0;
};

// Which of the arm's configurations a solution is in. Unused fields stay empty for a family
// that has no such choice.
enum class Elbow { left, right, up, down };  // scara: left/right; xarm: up/down
const char* to_string(Elbow elbow);
// The elbow word as people write it ("left", "right", "up", "down", as to_string gives
// them), or nothing. The one reading of the word: the CLI, path files, programs, Python.
std::optional<Elbow> parse_elbow(std::string_view word);
struct Configuration {
  std::optional<Elbow> elbow;
  std::optional<bool> wrist_flipped;  // scara: the wrist's second solution
  std::optional<bool> reaching_back;  // xarm: base turned half a turn, arm over the top
};

struct IkSolution {
  JointVector joints;
  Configuration configuration;
};

// What the caller wants reached. Orientation is required for the SCARA's 6-joint chain;
// the xArm (5 joints) reaches position plus tool pitch and roll only: its yaw follows from
// the position, so an orientation with another yaw is unreachable unless `nearest` is set.
struct IkRequest {
  Pose target;
  bool nearest_orientation = false;  // xarm: reach the position, the nearest orientation
};

// Why a pose could not be reached, in words for people, with the numbers that say by how
// much (beyond reach by N mm, joint J outside its limits, orientation not reachable).
// Returned as armctl::Error{invalid_argument, message}.

enum class Singularity {
  none,
  arm_stretched,    // elbow fully stretched or folded: the planar arm loses a direction
  wrist_aligned,    // two wrist axes in line: one rotation is lost
  over_base_axis,   // xarm: the tool point on the base axis: turning the base moves only
                    // the orientation (the base angle then follows from the approach)
};
const char* to_string(Singularity s);

class Kinematics {
 public:
  virtual ~Kinematics() = default;
  virtual std::string_view family() const = 0;  // its name in messages: "scara", "xarm"
  virtual int joint_count() const = 0;  // chain joints
  virtual Pose forward(const JointVector& joints) const = 0;
  // Every solution inside the limits, nearest to `near` first (by weighted joint
  // distance); an error that says why when there is none.
  virtual Result<std::vector<IkSolution>> inverse(const IkRequest& request,
                                                  const JointVector& near) const = 0;
  // Geometric Jacobian in the base frame: rows vx vy vz wx wy wz of the tool point.
  virtual Jacobian jacobian(const JointVector& joints) const = 0;
  // Singularity at `joints` (within `tolerance` of the singular set, in rad or m).
  virtual Singularity singularity(const JointVector& joints, double tolerance = 1e-3) const = 0;
};

// The URDF's <limit> lower..upper of each chain joint, base to tool.
std::vector<PositionLimits> urdf_position_limits(const UrdfChain& chain);

// Each family's kinematics is made by its own factory (make_scara_kinematics,
// make_xarm_kinematics, or one an arm family registers: arm/arm_families.hpp) from `chain`
// (read_urdf_chain) and the chain joints' position limits (one per chain joint, base to tool;
// the arm file's, which may be tighter than the URDF's). A factory refuses (invalid_config,
// naming the joint) a chain without the family's shape: joint count and types, axes parallel
// or perpendicular, a wrist whose axes meet, no sideways offsets. The lengths come from the
// chain, so an edited (calibrated) URDF works as long as the shape holds.

}  // namespace armctl::motion

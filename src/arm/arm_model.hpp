// What armctl knows about one arm, in SI units: its joints (names, kinds, limits), how each
// joint's value maps to the units of every device that can drive it, the kinematics of its
// chain, the tool frame and the gripper. Loaded from an arm file (docs/arm-files.md) plus
// the URDF the arm file names; both are checked against each other.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "arm/arm_families.hpp"
#include "arm/protocols.hpp"
#include "core/error.hpp"
#include "core/quantity.hpp"
#include "motion/kinematics.hpp"
#include "motion/link_bodies.hpp"
#include "scene/scene_limits.hpp"
#include "motion/urdf_chain.hpp"

namespace armctl::arm {

struct JointLimits {
  double lower = 0, upper = 0;  // rad or m
  double velocity = 0;          // rad/s or m/s
  double acceleration = 0;      // per s^2
  double jerk = 0;              // per s^3
  bool contains(double q, double slack = 0) const { return q >= lower - slack && q <= upper + slack; }
};

// A straight line between two points: device units <-> actuator value (SI). Direction and
// zero are in the two points (a reversed joint lists its device values descending).
struct DeviceMap {
  int id = 0;  // the joint's ID on the device: Robot Commands servo ID, joint-bus joint number
  double device_a = 0, actuator_a = 0, device_b = 1, actuator_b = 1;
  // Joint bus only: the joint's own speed at set_speed 100 % and its acceleration, as in
  // its tuning (the simulator section of config/scara.arm.json), so that moves can be planned to arrive together.
  double max_speed_cps = 0, max_accel_cps2 = 0;
  double device_per_unit() const { return (device_b - device_a) / (actuator_b - actuator_a); }
  double to_device(double actuator) const { return device_a + (actuator - actuator_a) * device_per_unit(); }
  double to_actuator(double device) const { return actuator_a + (device - device_a) / device_per_unit(); }
};

enum class JointRole { chain, gripper };

struct JointModel {
  std::string name;
  Dimension dimension = Dimension::angle;  // revolute: angle; prismatic: length
  JointRole role = JointRole::chain;
  JointLimits limits;
  double urdf_lower = 0, urdf_upper = 0;  // the URDF's position limits (mechanical travel)
  // How the joint maps to each protocol that can drive it, by the protocol's name (the arm
  // file's keys: arm/protocols.hpp).
  std::map<std::string, DeviceMap, std::less<>> devices;
  const DeviceMap* map(Protocol p) const {
    auto it = devices.find(p.name());
    return it == devices.end() ? nullptr : &it->second;
  }
  DeviceMap* map(Protocol p) {
    auto it = devices.find(p.name());
    return it == devices.end() ? nullptr : &it->second;
  }
};

// Two joints driven by two actuators together (the SCARA's differential wrist):
// actuator[first, second] = matrix * joint[first, second]. Joints without a coupling have
// actuator = joint.
struct Coupling {
  int first = 0, second = 0;  // joint indices
  double matrix[2][2] = {{1, 0}, {0, 1}};
};

struct GripperModel {
  int joint = 0;               // index of the gripper joint
  double open = 0, closed = 0;  // its positions (rad or m)
  double at(double closed_fraction) const { return open + closed_fraction * (closed - open); }
  double fraction(double position) const {
    return closed == open ? 0.0 : (position - open) / (closed - open);
  }
};

struct ArmModel {
  std::string name;
  std::string family;  // the arm file's family (arm/arm_families.hpp)
  FamilyRules rules;   // that family's rules
  std::vector<JointModel> joints;  // the chain's joints base to tool, then the gripper
  std::vector<Coupling> couplings;
  std::optional<GripperModel> gripper;
  motion::Pose tool;  // the tool frame in the URDF's tool link
  std::shared_ptr<const motion::Kinematics> kinematics;
  // The chain the kinematics was made from, with the arm file's link lengths applied, and
  // those lengths ("link_lengths": the calibrated lengths of URDF joint origins,
  // docs/calibration.md; empty when the URDF's own are used).
  std::shared_ptr<const motion::UrdfChain> chain;
  std::vector<motion::OriginLength> link_lengths;
  // The farthest the tool point can be from the base frame's origin (m), for any joint
  // values: the chain's offsets end to end, plus each prismatic joint's travel and the
  // tool's offset. An upper bound: a target beyond it is refused before any planning.
  double reach = 0;
  std::filesystem::path file;  // the arm file it came from ("" if parsed from text)
  std::filesystem::path urdf;
  // The URDF the arm drives with: that file's text with link_lengths written into the joints'
  // origins (motion/urdf_for_viewers.hpp), for viewers that read a URDF themselves (the
  // dashboard's 3D view, ROS's robot_description).
  std::string urdf_text;
  // Every link with its URDF <collision> shapes (docs/scene.md), the link pairs the arm
  // file's "collision" section allows to touch (found by sampling, reviewed in docs/scene.md),
  // and the tool's link, where parts held by the tool hang.
  std::shared_ptr<const motion::LinkBodies> bodies;
  std::vector<std::pair<std::string, std::string>> allowed_collisions;
  std::string tool_link;
  // The fence and reduced mode the arm file sets (docs/scene.md "Fence and reduced mode"),
  // read and checked as a scene file's: in force wherever a scene sets none of its own.
  std::optional<scene::Fence> fence;
  std::optional<scene::ReducedMode> reduced;

  int chain_joints() const { return kinematics ? kinematics->joint_count() : 0; }
  int joint_count() const { return static_cast<int>(joints.size()); }
  // Index of the joint named `name` (case-insensitive), or nothing.
  std::optional<int> find_joint(std::string_view joint_name) const;
  bool supports(Protocol p) const;

  // Joint values (SI, every joint) -> device units per joint, and back (couplings applied).
  std::vector<double> to_device(Protocol p, const std::vector<double>& joints) const;
  std::vector<double> from_device(Protocol p, const std::vector<double>& device) const;
};

// Ok when `position` (m, base frame) lies within model.reach of the base, else
// invalid_argument naming `what`, the coordinate that is farthest out with its value in mm,
// and the reach: "segment 1 (LIN): target: x 1e+200 mm is beyond reach: arm 'xarm' reaches
// at most 366 mm from its base".
Status within_reach(const ArmModel& model, const Eigen::Vector3d& position, std::string_view what);

// Parses an arm file's text. `urdf_text` is the URDF it names (read by the caller relative
// to the arm file); every error (invalid_config) names the key or URDF element and what is
// allowed.
Result<ArmModel> parse_arm_model(std::string_view arm_json, std::string_view source,
                                 std::string_view urdf_text, std::string_view urdf_source);

// Reads an arm file and the URDF it names (relative to the arm file's folder).
Result<ArmModel> load_arm_model(const std::filesystem::path& arm_file);

// `xarm` or `scara` -> the shipped arm file (config/<name>.arm.json, found as other configs
// are: core/config_files.hpp); anything else is taken as a path.
std::filesystem::path arm_file_path(std::string_view arm);

}  // namespace armctl::arm

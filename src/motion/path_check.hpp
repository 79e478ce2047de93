// The check of a Cartesian path before anything moves: inverse kinematics along the whole
// path, continuous from the arm's joints, against the joints' position and velocity limits.
// It either refuses the path (naming the segment, where on it, the joint and the value) or
// returns the joints along it with what the executor needs to time it (docs/paths.md).
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/quantity.hpp"
#include "motion/cartesian_path.hpp"
#include "motion/kinematics.hpp"

namespace armctl::motion {

// Between two samples the tool point moves at most this far and turns at most this much.
inline constexpr double kPathSampleLength = 1e-3;                         // m
inline constexpr double kPathSampleAngle = 1.0 * 3.14159265358979323846 / 180;  // rad
// ... and no joint moves more than this (rad, or m for a prismatic joint): the samples are
// halved where a joint moves fast (near a singularity) until it holds.
inline constexpr double kPathSampleJointAngle = 1.0 * 3.14159265358979323846 / 180;
inline constexpr double kPathSampleJointLength = 1e-3;
// The slowest the check lets a path go: a ds/dt below this (1 % of the programmed speed)
// needed anywhere refuses the path.
inline constexpr double kMinPathRate = 0.01;
// A path whose first joints are this close to a singular configuration (Kinematics::
// singularity's tolerance) starts at it; a line that cannot leave it is refused saying so.
inline constexpr double kSingularStart = 1e-3;
// A joint farther than this from its value at the start of the path means the path does
// not start where the arm is (rad, or m for a prismatic joint: 1 deg and 1 mm).
inline constexpr double kStartAngleSlack = 1.0 * 3.14159265358979323846 / 180;
inline constexpr double kStartLengthSlack = 1e-3;

// One chain joint's limits, SI; name and dimension for messages.
struct PathLimits {
  double lower = 0, upper = 0;   // rad or m
  double velocity = 0;           // rad/s or m/s, > 0
  double acceleration = 0;       // per s^2, > 0
  std::string name;              // "servo4", "SHOULDER"
  Dimension dimension = Dimension::angle;
};

// A stretch of the path where the joint velocity limits need ds/dt < 1.
struct SlowSpot {
  int segment = 0;               // 0-based, of the slowest point
  double from_s = 0, to_s = 0;   // the stretch (nominal s)
  double at_s = 0;               // the slowest point
  double rate = 1;               // the largest ds/dt allowed there (< 1)
  int joint = 0;                 // chain joint that limits it
  Singularity singularity = Singularity::none;  // the one nearby, if any
  std::string message;           // for people: where, how slow, why
};

struct CheckedPath {
  // Samples along the path, s ascending. At a rest (an exact stop) s appears twice: once
  // ending the stretch before it, once starting the one after, each sample with its own
  // one-sided derivatives (the path's direction changes there).
  std::vector<double> s;
  std::vector<JointVector> joints;   // chain joints at each sample (IK, continuous)
  std::vector<JointVector> dq_ds;    // per joint, rad (or m) per nominal s
  std::vector<JointVector> d2q_ds2;  // per joint, per nominal s^2
  // The largest ds/dt the joint velocity limits allow at each sample: min over the joints
  // of velocity / |dq/ds|. With s(t) the joint velocity is dq/ds * ds/dt and the joint
  // acceleration d2q/ds2 (ds/dt)^2 + dq/ds d2s/dt2: the executor bounds ds/dt and d2s/dt2
  // with these and the acceleration limits.
  std::vector<double> rate_limit;
  double max_rate = 1;               // min of rate_limit (< 1: the path is slowed somewhere)
  std::vector<SlowSpot> slowed;      // where and why the path is slowed

  // The joints at s: cubic Hermite interpolation between the samples (the samples' spacing
  // bounds its error, docs/paths.md).
  JointVector joints_at(double s) const;
  // The joints at s with dq/ds (the Hermite interpolation's derivative) and d2q/ds2
  // (linear between the samples): what an executor timing s(t) needs for the joint
  // velocity dq/ds s' and acceleration d2q/ds2 s'^2 + dq/ds s''.
  struct Joints {
    JointVector position, dq_ds, d2q_ds2;
  };
  Joints joints_with_rates(double s) const;
  // The smaller rate_limit of the two samples around s (the path's own bound there).
  double rate_limit_at(double s) const;
  // The joints at s by inverse kinematics, the solution nearest `near`; the interpolated
  // value if the kinematics the path was checked with is gone or finds none.
  JointVector joints_at(double s, const JointVector& near) const;

  struct Solver;                       // what joints_at(s, near) needs
  std::shared_ptr<const Solver> solver;  // holds a pointer to the kinematics: keep it alive
};

// Checks `path` for the chain of `kinematics` with the tool frame `tool` (the tool in the
// chain's last link: the chain's flange must be at pose * tool^-1, as Arm::inverse does),
// from the joints `start` (one per chain joint, where the arm is; the path must start
// there) with one PathLimits per chain joint. `nearest_orientation`: the xArm's 5-joint
// chain, which reaches every position with the nearest reachable orientation.
Result<CheckedPath> check_path(const CartesianPath& path, const Kinematics& kinematics, const Pose& tool,
                               const JointVector& start, std::span<const PathLimits> limits,
                               bool nearest_orientation);

}  // namespace armctl::motion

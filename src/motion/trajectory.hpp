// Time-optimal, jerk-limited, synchronized trajectories for 1..7 joints (docs/trajectories.md).
//
// From any current state (position, velocity, acceleration) per joint to a target position
// and velocity (acceleration 0), optionally through waypoints passed without stopping, under
// per-joint limits of velocity, acceleration and jerk. Every joint arrives at the same
// instant: the slowest joint's minimum time, or `min_duration` if longer, or the next
// duration every joint can make (a joint cannot take every duration: "blocked intervals").
// Pure code: value types in and out, no I/O, no allocation once `out` has held a trajectory
// with as many sections. SI units (m or rad, s).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/error.hpp"
#include "motion/jerk_profile.hpp"

namespace armctl::motion {

inline constexpr int kMaxTrajectoryJoints = 7;
using JointArray = std::array<double, kMaxTrajectoryJoints>;

// Magnitudes refused beyond these (docs/trajectories.md "Validation"): inside them no
// intermediate value can overflow.
inline constexpr double kMaxTrajectoryMagnitude = 1e12;  // positions, velocities, limits
inline constexpr double kMinTrajectoryLimit = 1e-9;      // velocity, acceleration, jerk limits

struct TrajectoryInput {
  int joints = 1;                                     // 1..7
  JointArray position{}, velocity{}, acceleration{};  // current state (SI)
  JointArray target_position{}, target_velocity{};    // target; target acceleration is 0
  JointArray max_velocity{}, max_acceleration{}, max_jerk{};
  std::span<const JointArray> waypoints{};  // passed through without stopping
  double min_duration = 0;                  // s
};

struct TrajectoryState {
  JointArray position{}, velocity{}, acceleration{}, jerk{};
};

// Per joint, over the whole trajectory, computed analytically segment by segment.
struct TrajectoryExtrema {
  JointArray max_abs_velocity{}, max_abs_acceleration{}, max_abs_jerk{};
  JointArray min_position{}, max_position{};
};

class Trajectory {
 public:
  int joints() const { return joints_; }
  double duration() const;                         // exact, s
  TrajectoryState at(double t) const;              // t clamped to [0, duration()]
  int sections() const { return section_count_; }  // waypoints + 1
  double section_end(
      int k) const;  // time the k-th waypoint (or the target, k = sections()-1) is reached
  double section_start(int k) const;
  TrajectoryExtrema extrema() const;
  // The constant-jerk segments of one joint in one section (start times from the section's
  // start), for checks and for executors that stream segments.
  std::span<const JerkSegment> segments(int section, int joint) const;

 private:
  friend Status calculate_trajectory(const TrajectoryInput& in, Trajectory& out);
  struct Section {
    double start = 0, end = 0;
    std::array<JerkSegments, kMaxTrajectoryJoints> joints{};
  };
  int joints_ = 0;
  int section_count_ = 0;
  std::vector<Section> sections_;
};

// Fills `out` (reusing its storage). Refuses (ErrorKind::invalid_argument, naming the joint,
// the value and what is allowed, `out` left as it was) a joint count outside 1..7, a limit
// that is not finite and > 0, a state, target or waypoint that is not finite, |velocity|,
// |target velocity| above the velocity limit, |acceleration| above the acceleration limit,
// and a start whose velocity limit cannot be kept (velocity + a|a|/(2 jerk) beyond it).
Status calculate_trajectory(const TrajectoryInput& in, Trajectory& out);

// The velocities chosen at the waypoints (docs/trajectories.md "Waypoints"): per joint the
// mean of the neighbouring sections' average velocities, 0 where the direction reverses or
// a joint stands still; each section's average taken over its rest-to-rest minimum time.
// `out` gets waypoints.size() entries.
void waypoint_velocities(const TrajectoryInput& in, std::span<JointArray> out);

// The fastest rest-to-rest move over `distance` (either sign) under `limits`, closed form.
double rest_to_rest_time(double distance, const JerkLimits& limits);

}  // namespace armctl::motion

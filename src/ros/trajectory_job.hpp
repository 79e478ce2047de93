// Runs a checked trajectory on the arm worker's thread: planned again from a fresh read
// (the arm may have moved since the goal was checked: a replaced motion stops on its path),
// streamed by the motion executor, then the end checked against the goal tolerances.
// Path tolerance: the executor's following-error threshold (the smallest tolerance given
// for a revolute joint, and for a prismatic one); beyond it the arm halts. Goal tolerance:
// Arm::wait with the smallest given tolerance and goal_time_tolerance as its timeout.
#pragma once

#include <mutex>
#include <optional>
#include <string>
#include <vector>
#include <cstdint>

#include "arm/motion_executor.hpp"
#include "ros/trajectory_goal.hpp"
#include "session/arm_worker.hpp"

namespace armctl::ros_node {

struct TrajectoryDefaults {
  double goal_time = 1.0;  // s after the last point, when the goal gives none
  StartTolerance start;
};

// A read-back of the executor with the nominal time it was made at, for feedback: the
// plan there is where the arm should have been.
struct FollowSample {
  std::uint64_t count = 0;  // +1 per read
  double t = 0;             // nominal s at the read
  std::vector<double> positions, velocities;  // SI, every joint
};

// What happened, for the action result (read after the job's future is ready).
struct TrajectoryOutcome {
  GoalError code = GoalError::none;
  std::string message;
  bool stopped = false;  // by a stop/cancel/replacement, at rest on the path
  std::optional<arm::MotionReport> report;
  std::optional<TrajectoryPlan> plan;
  FollowSample last_read;
  std::mutex mutex;  // plan and last_read are set on the worker thread, read for feedback meanwhile
};

Status run_trajectory(arm::Arm& arm, session::JobContext& ctx, const TrajectoryRequest& request,
                      const GoalTolerances& tolerances, const TrajectoryDefaults& defaults,
                      TrajectoryOutcome& outcome);

}  // namespace armctl::ros_node

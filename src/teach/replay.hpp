// Replaying a recording (motion/recording.hpp) through the motion layer: the samples
// smoothed, decimated into waypoints, and one jerk-limited joint move planned through them
// (arm::plan_moves), within the arm's limits. Pure planning. Docs: docs/teach.md "Replay".
#pragma once

#include <cstddef>
#include <vector>

#include "arm/arm_model.hpp"
#include "arm/motion_executor.hpp"
#include "arm/plan_moves.hpp"
#include "core/error.hpp"
#include "files/recording_file.hpp"

namespace armctl::teach {

struct ReplayOptions {
  double speed = 1.0;  // (0, 1]: fraction of the velocity limits
  std::size_t smooth_half_window = 2;  // samples each side (motion::smooth)
  double angle_tolerance = 0.0087;     // rad (0.5 deg): decimation, per joint
  double length_tolerance = 0.0005;    // m
  std::size_t max_waypoints = 400;     // the tolerance grows until the waypoints fit
};

struct ReplayPlan {
  arm::Plan plan;  // for the runner (arm::run_motion): the two motions below
  arm::PlannedMotion to_start;  // from where the arm stands to the first sample (rest to rest)
  arm::PlannedMotion motion;    // through the waypoints to the last sample
  std::vector<std::vector<double>> waypoints;  // SI, every joint, the first and last sample excluded
  double recorded_seconds = 0;
  double tolerance_scale = 1;  // how much the decimation tolerance had to grow
};

// Refuses (invalid_argument, nothing planned) a recording of another arm, with other
// joints, or with a sample outside the joint limits (naming the sample's time, the joint,
// the value and what is allowed).
Result<ReplayPlan> plan_replay(const arm::ArmModel& model, const std::vector<double>& from,
                               const motion::Recording& recording, const ReplayOptions& options = {});

}  // namespace armctl::teach

#include "teach/replay.hpp"

#include <cmath>

#include <fmt/core.h>

#include "arm/arm.hpp"
#include "arm/motion_planning.hpp"

namespace armctl::teach {

namespace {

Error refuse(const std::string& what) { return Error{ErrorKind::invalid_argument, what}; }

}  // namespace

Result<ReplayPlan> plan_replay(const arm::ArmModel& model, const std::vector<double>& from,
                               const motion::Recording& recording, const ReplayOptions& options) {
  if (!(options.speed > 0 && options.speed <= 1))
    return refuse(fmt::format("speed {:.0f} %: allowed is above 0 up to 100 %", options.speed * 100));
  if (recording.arm != model.name)
    return refuse(fmt::format("the recording is of arm '{}', this arm is '{}'", recording.arm, model.name));
  if (recording.joints.size() != model.joints.size())
    return refuse(fmt::format("the recording has {} joints, arm '{}' has {}", recording.joints.size(), model.name,
                              model.joints.size()));
  for (std::size_t i = 0; i < model.joints.size(); ++i)
    if (recording.joints[i].name != model.joints[i].name || recording.joints[i].dimension != model.joints[i].dimension)
      return refuse(fmt::format("the recording's joint {} is '{}' ({}); arm '{}' has '{}' ({}) there", i + 1,
                                recording.joints[i].name, to_string(recording.joints[i].dimension), model.name,
                                model.joints[i].name, to_string(model.joints[i].dimension)));
  if (recording.samples.empty()) return refuse("the recording has no samples");
  for (const auto& s : recording.samples) {
    if (s.positions.size() != model.joints.size())
      return refuse(fmt::format("the sample at {:.3f} s has {} values, the arm {} joints", s.time, s.positions.size(),
                                model.joints.size()));
    for (std::size_t i = 0; i < model.joints.size(); ++i) {
      const auto& l = model.joints[i].limits;
      if (!l.contains(s.positions[i]))
        return refuse(fmt::format("the sample at {:.3f} s: joint {} at {} is outside its limits {} .. {}", s.time,
                                  model.joints[i].name, arm::format_joint_value(model, int(i), s.positions[i]),
                                  arm::format_joint_value(model, int(i), l.lower),
                                  arm::format_joint_value(model, int(i), l.upper)));
    }
  }
  ReplayPlan plan;
  plan.recorded_seconds = recording.samples.back().time - recording.samples.front().time;
  const auto smoothed = motion::smooth(recording.samples, options.smooth_half_window);
  std::vector<double> tolerance;
  for (const auto& j : model.joints)
    tolerance.push_back(j.dimension == Dimension::angle ? options.angle_tolerance : options.length_tolerance);
  std::vector<std::size_t> kept = motion::keep_samples(smoothed, tolerance);
  while (kept.size() > options.max_waypoints + 2) {
    plan.tolerance_scale *= 1.5;
    for (double& t : tolerance) t *= 1.5;
    kept = motion::keep_samples(smoothed, tolerance);
  }
  for (std::size_t k = 1; k + 1 < kept.size(); ++k) plan.waypoints.push_back(smoothed[kept[k]].positions);

  arm::JointMove to_start;
  to_start.target = smoothed.front().positions;
  to_start.speed = options.speed;
  auto start = arm::plan_joint_move(model, from, to_start);
  if (!start) return start.error();
  plan.to_start = std::move(start).value();
  plan.to_start.what = "to the recording's start";

  arm::JointMove move;
  move.waypoints = plan.waypoints;
  move.target = smoothed.back().positions;
  move.speed = options.speed;
  // Never faster than it was recorded: a hand's motion stays a hand's pace.
  move.min_duration = plan.recorded_seconds / options.speed;
  auto motion = arm::plan_joint_move(model, smoothed.front().positions, move);
  if (!motion) return motion.error();
  plan.motion = std::move(motion).value();
  plan.motion.what = fmt::format("replay through {} waypoints", plan.waypoints.size());
  return plan;
}

}  // namespace armctl::teach

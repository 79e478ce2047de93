#include "teach/replay.hpp"

#include <cmath>

#include <fmt/core.h>

#include "arm/arm.hpp"
#include "arm/plan_moves.hpp"

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

  // To the first sample, then through the waypoints to the last: one plan (arm::plan_moves).
  arm::PtpMove to_start;
  to_start.target = std::vector<std::optional<double>>(smoothed.front().positions.begin(),
                                                       smoothed.front().positions.end());
  to_start.speed = options.speed;
  arm::PtpMove replay;
  replay.waypoints = plan.waypoints;
  replay.target = std::vector<std::optional<double>>(smoothed.back().positions.begin(), smoothed.back().positions.end());
  replay.speed = options.speed;
  // Never faster than it was recorded: a hand's motion stays a hand's pace.
  replay.min_duration = plan.recorded_seconds / options.speed;
  const std::vector<arm::Move> moves{{to_start, "to the recording's start"},
                                     {replay, fmt::format("replay through {} waypoints", plan.waypoints.size())}};
  auto planned = arm::plan_moves(arm::ArmKinematics(model), from, moves);
  if (!planned) return planned.error();
  plan.plan = std::move(planned).value();
  for (auto& piece : plan.plan.pieces) piece.motion.what = piece.label;
  plan.to_start = plan.plan.pieces[0].motion;
  plan.motion = plan.plan.pieces[1].motion;
  return plan;
}

}  // namespace armctl::teach

#include "web/motion_jobs.hpp"

#include <cmath>

#include <fmt/core.h>

#include "arm/motion_executor.hpp"
#include "arm/motion_planning.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"

namespace armctl::web {

namespace {

using nlohmann::json;


// Runs a planned motion on the worker: through the executor with the job's context (stop
// slows down on the path, pause holds on it, positions are published), then waits until
// the arm stands at the end.
Status run_planned(arm::Arm& arm, session::JobContext& ctx, const arm::PlannedMotion& motion) {
  auto report = arm::execute_motion(arm, motion, ctx.executor_options());
  if (!report) return report.error();
  if (!report->completed || ctx.stopping()) return Ok{};  // stopped on request: not an error
  arm::WaitOptions wait;
  wait.timeout = std::chrono::seconds(10);
  if (auto s = arm.wait(ctx.wait_options(wait)); !s && !ctx.stopping()) return s.error();
  return Ok{};
}

// `note`: why the move takes longer than asked (a duration below the arm file's limits).
json moving(const arm::PlannedMotion& m, const std::string& note = {}) {
  json out{{"moving", true}, {"duration_s", m.duration}};
  if (!note.empty()) out["note"] = note;
  return out;
}

// A joint-space move to `target` (SI, every joint): planned, accepted, run. With a
// `duration`, the rule of every app: stretched to the arm file's limits, and the reply says so.
Status joint_move(arm::Arm& arm, session::JobContext& ctx, const Accept& accept, const std::vector<double>& from,
                  const std::vector<double>& target, double speed, std::optional<double> duration) {
  std::vector<std::optional<double>> check(target.begin(), target.end());
  if (auto ok = arm.check_targets(check); !ok) return ok.error();
  arm::JointMove move;
  move.target = target;
  move.speed = duration ? 1.0 : speed;
  std::string note;
  if (duration) {
    auto timed = arm::joint_move_duration(arm.model(), from, target, *duration, fmt::format("duration {:g} s", *duration));
    if (!timed) return timed.error();
    move.min_duration = timed->seconds;
    note = timed->note;
  }
  auto planned = arm::plan_joint_move(arm.model(), from, move);
  if (!planned) return planned.error();
  accept(moving(*planned, note));
  return run_planned(arm, ctx, *planned);
}

// The tool to `goal`: PTP to the IK solution nearest where the arm stands, or a straight line.
Status tool_move(arm::Arm& arm, session::JobContext& ctx, const Accept& accept, const arm::JointState& here,
                 const arm::CartesianGoal& goal, bool linear, double speed) {
  if (!linear) {
    auto solutions = arm.inverse(goal, here);
    if (!solutions) return solutions.error();
    std::vector<double> target = here.positions;
    const motion::JointVector& q = solutions->front().joints;
    for (int i = 0; i < q.size(); ++i) target[std::size_t(i)] = q[i];
    return joint_move(arm, ctx, accept, here.positions, target, speed, std::nullopt);
  }
  // The request's speed, a fraction, checked as given (not as the m/s it becomes).
  if (auto ok = check_fraction_in(speed, "speed", motion::kMinSpeedFraction, motion::kMaxSpeedFraction); !ok)
    return ok.error();
  arm::CartesianMove line;
  line.goal = goal;
  line.speed = speed * kMaxLinearSpeed;
  const std::vector<arm::CartesianMove> moves{line};
  const std::vector<motion::PathSegment> segments = arm::path_segments(arm, here.positions, moves);
  auto plan = arm::plan_path(arm.model(), here.positions, segments);
  if (!plan) return plan.error();
  accept(moving(plan->motion));
  return run_planned(arm, ctx, plan->motion);
}

}  // namespace

MotionJob joint_move_job(JointsRequest r) {
  return [r](arm::Arm& arm, session::JobContext& ctx, const Accept& accept) -> Status {
    if (auto ok = arm.check_targets(r.targets); !ok) return ok.error();
    auto here = arm.read();
    if (!here) return here.error();
    std::vector<double> target = here->positions;
    for (std::size_t i = 0; i < target.size() && i < r.targets.size(); ++i)
      if (r.targets[i]) target[i] = *r.targets[i];
    return joint_move(arm, ctx, accept, here->positions, target, r.speed, r.duration);
  };
}

MotionJob tool_move_job(ToolRequest r) {
  return [r](arm::Arm& arm, session::JobContext& ctx, const Accept& accept) -> Status {
    auto here = arm.read();
    if (!here) return here.error();
    arm::CartesianGoal goal;
    goal.position = r.position;
    goal.roll = r.roll;
    goal.pitch = r.pitch;
    goal.yaw = r.yaw;
    return tool_move(arm, ctx, accept, *here, goal, r.linear, r.speed);
  };
}

MotionJob jog_job(JogRequest r) {
  return [r](arm::Arm& arm, session::JobContext& ctx, const Accept& accept) -> Status {
    auto here = arm.read();
    if (!here) return here.error();
    const motion::JointVector q = arm.chain_of(here->positions);
    const motion::Pose pose = arm.forward(q);
    const motion::Rpy rpy = arm.tool_rpy(pose, q);
    arm::CartesianGoal goal;
    goal.position = pose.position;
    if (r.axis < 3) goal.position[r.axis] += r.step;
    goal.roll = rpy.roll + (r.axis == 3 ? r.step : 0);
    goal.pitch = rpy.pitch + (r.axis == 4 ? r.step : 0);
    // The 5-joint xArm's yaw is where it points: it follows the position unless jogged.
    if (r.axis == 5) goal.yaw = rpy.yaw + r.step;
    else if (arm.model().family != motion::KinematicFamily::xarm) goal.yaw = rpy.yaw;
    return tool_move(arm, ctx, accept, *here, goal, r.linear, r.speed);
  };
}

MotionJob gripper_job(double closed) {
  return [closed](arm::Arm& arm, session::JobContext& ctx, const Accept& accept) -> Status {
    if (!arm.model().gripper)
      return Error{ErrorKind::unsupported, fmt::format("arm {} has no gripper", arm.model().name)};
    arm::MoveOptions o;
    o.speed = 0.5;
    if (auto s = arm.gripper(closed, o); !s) return s.error();
    accept(json{{"moving", true}});
    arm::WaitOptions wait;
    if (auto s = arm.wait(ctx.wait_options(wait)); !s && !ctx.stopping()) return s.error();
    return Ok{};
  };
}

}  // namespace armctl::web

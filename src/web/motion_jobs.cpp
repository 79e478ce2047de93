#include "web/motion_jobs.hpp"

#include <cmath>

#include <fmt/core.h>

#include "arm/avoid_path.hpp"
#include "arm/plan_moves.hpp"
#include "arm/run_motion.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"
#include "web/display_value.hpp"

namespace armctl::web {

namespace {

using nlohmann::json;


// The hooks of a web job: the job's context (stop slows down on the path, pause holds on
// it, positions and progress are published); a stop is not an error.
arm::RunHooks job_hooks(session::JobContext& ctx) {
  arm::RunHooks hooks;
  // Stop (pause and resume are the executor's: they hold a motion on its path).
  hooks.command = [&ctx] { return ctx.stopping() ? arm::MotionCommand::stop : arm::MotionCommand::none; };
  hooks.executor = ctx.executor_options();
  hooks.wait = ctx.wait_options();
  return hooks;
}

// Plans `moves` from where the arm stands (arm::plan_moves), answers the request (the plan's
// duration, and a note when it takes longer than asked; `also`'s keys too), then runs it
// (arm::run_motion).
Status plan_and_run(arm::Arm& arm, session::JobContext& ctx, const Accept& accept, const arm::JointState& here,
                    const std::vector<arm::Move>& moves, const json& also = json::object()) {
  auto plan = arm::plan_moves(*arm.kinematics(), here.positions, moves);
  if (!plan) return plan.error();
  // As every app answers a move: how long it takes and where it ends (each joint as the API
  // shows joints: deg or mm).
  json targets = json::object();
  const arm::ArmModel& model = arm.model();
  for (std::size_t i = 0; i < model.joints.size(); ++i)
    targets[model.joints[i].name] = display_value(model.joints[i].dimension, plan->end()[i]);
  json answer{{"moving", true}, {"duration_s", plan->duration}, {"targets", targets}};
  if (const std::string note = plan->notes(); !note.empty()) answer["note"] = note;
  answer.update(also);
  accept(answer);
  auto report = arm::run_motion(arm, *plan, job_hooks(ctx));
  if (!report && !ctx.stopping()) return report.error();
  return Ok{};
}

// The tool to `goal`: PTP to the IK solution nearest where the arm stands, or a straight line.
// With `avoid_time`, a PTP whose direct motion would collide goes around the obstacles
// (arm::avoiding_move, as `armctl arm move-to --avoid`), searching that long at most.
Status tool_move(arm::Arm& arm, session::JobContext& ctx, const Accept& accept, const arm::JointState& here,
                 const arm::CartesianGoal& goal, bool linear, double speed, std::optional<double> avoid_time = {}) {
  if (!linear) {
    arm::PtpMove ptp;
    ptp.target = goal;
    ptp.speed = speed;
    if (avoid_time) {
      arm::AvoidOptions around;
      around.time_budget = *avoid_time;
      auto avoided = arm::avoiding_move(*arm.kinematics(), here.positions, ptp, around);
      if (!avoided) return avoided.error();
      ptp = avoided->move;
      // As the CLI's --json says it: how many waypoints the detour has (0: the direct move
      // is clear) and how long the search took.
      return plan_and_run(arm, ctx, accept, here, {arm::Move{ptp}},
                          json{{"avoided", {{"waypoints", avoided->waypoints}, {"planning_s", avoided->planning_s}}}});
    }
    return plan_and_run(arm, ctx, accept, here, {arm::Move{ptp}});
  }
  // The request's speed, a fraction, checked as given (not as the m/s it becomes).
  if (auto ok = check_fraction_in(speed, "speed", motion::kMinSpeedFraction, motion::kMaxSpeedFraction); !ok)
    return ok.error();
  arm::CartesianMove line;
  line.goal = goal;
  line.speed = speed * kMaxLinearSpeed;
  return plan_and_run(arm, ctx, accept, here, {arm::Move{line}});
}

}  // namespace

MotionJob joint_move_job(JointsRequest r) {
  return [r](arm::Arm& arm, session::JobContext& ctx, const Accept& accept) -> Status {
    if (auto ok = arm.check_targets(r.targets); !ok) return ok.error();
    auto here = arm.read();
    if (!here) return here.error();
    arm::PtpMove ptp;
    ptp.target = r.targets;
    ptp.speed = r.speed;
    ptp.duration = r.duration;
    if (r.duration) ptp.duration_words = fmt::format("duration {:g} s", *r.duration);
    return plan_and_run(arm, ctx, accept, *here, {arm::Move{ptp}});
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
    return tool_move(arm, ctx, accept, *here, goal, r.linear, r.speed, r.avoid_time);
  };
}

MotionJob jog_job(JogRequest r) {
  return [r](arm::Arm& arm, session::JobContext& ctx, const Accept& accept) -> Status {
    auto here = arm.read();
    if (!here) return here.error();
    const arm::ArmKinematics& kin = *arm.kinematics();
    const motion::Pose pose = kin.pose_at(here->positions);
    const motion::Rpy rpy = kin.tool_rpy_at(here->positions);
    Eigen::Vector3d position = pose.position;
    if (r.axis < 3) position[r.axis] += r.step;
    // The orientation kept (where the yaw follows the position, it follows it unless jogged).
    arm::CartesianGoal goal = kin.keeping_orientation(position, rpy);
    if (r.axis == 3) goal.roll = rpy.roll + r.step;
    if (r.axis == 4) goal.pitch = rpy.pitch + r.step;
    if (r.axis == 5) goal.yaw = rpy.yaw + r.step;
    return tool_move(arm, ctx, accept, *here, goal, r.linear, r.speed);
  };
}

MotionJob gripper_job(double closed) {
  return [closed](arm::Arm& arm, session::JobContext& ctx, const Accept& accept) -> Status {
    if (!arm.model().gripper)
      return Error{ErrorKind::unsupported, fmt::format("arm {} has no gripper", arm.model().name)};
    if (!std::isfinite(closed) || closed < 0 || closed > 1)
      return Error{ErrorKind::invalid_argument,
                   fmt::format("gripper: {} is outside 0..1 (0 = open, 1 = closed)", closed)};
    auto here = arm.read();
    if (!here) return here.error();
    std::vector<std::optional<double>> targets(here->positions.size());
    targets[std::size_t(arm.model().gripper->joint)] = arm.model().gripper->at(closed);
    arm::PtpMove ptp;
    ptp.target = targets;
    ptp.speed = motion::kDefaultGripperSpeed;
    arm::PlanOptions board;
    board.ptp = arm::PtpRun::board;
    auto plan = arm::plan_moves(*arm.kinematics(), here->positions, std::vector<arm::Move>{{ptp}}, board);
    if (!plan) return plan.error();
    accept(json{{"moving", true}});
    auto report = arm::run_motion(arm, *plan, job_hooks(ctx));
    if (!report && !ctx.stopping()) return report.error();
    return Ok{};
  };
}

}  // namespace armctl::web

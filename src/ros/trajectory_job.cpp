#include "ros/trajectory_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include <fmt/core.h>

#include "arm/run_motion.hpp"

namespace armctl::ros_node {

namespace {

// Each joint's tolerance as the executor and Arm::wait take them: the one given (one that is
// not checked becomes a bound no motion reaches), or 0 for the default of its kind.
std::vector<double> per_joint(const std::vector<std::optional<double>>& given) {
  std::vector<double> out(given.size(), 0.0);
  for (std::size_t j = 0; j < given.size(); ++j)
    if (given[j]) out[j] = std::isinf(*given[j]) ? 1e9 : *given[j];
  return out;
}

Status fail(TrajectoryOutcome& outcome, GoalError code, const Error& e) {
  std::lock_guard<std::mutex> lock(outcome.mutex);
  outcome.code = code;
  outcome.message = e.message;
  return e;
}

}  // namespace

Status run_trajectory(arm::Arm& arm, session::JobContext& ctx, const TrajectoryRequest& request,
                      const GoalTolerances& tolerances, const TrajectoryDefaults& defaults,
                      TrajectoryOutcome& outcome) {
  auto now = arm.read();
  if (!now) return fail(outcome, GoalError::invalid_goal, now.error());
  ctx.positions(*now);
  auto plan = plan_trajectory(*arm.kinematics(), now->positions, request, defaults.start);
  if (!plan) return fail(outcome, refusal_of(plan.error()).code, plan.error());
  {
    std::lock_guard<std::mutex> lock(outcome.mutex);
    outcome.plan = *plan;
  }

  arm::ExecutorOptions eo;
  eo.following_error = per_joint(tolerances.path);
  // Each read-back with its nominal time: the last point's, advanced at its rate to the read.
  struct Point {
    double t = 0, rate = 0;
    TimePoint at{};
  };
  auto last_point = std::make_shared<Point>();
  const Clock& clock = arm.clock();
  eo.on_point = [last_point, &clock](const arm::MotionProgress& p) { *last_point = {p.t, p.rate, clock.now()}; };
  eo.on_read = [last_point, &outcome](const arm::JointState& s) {
    const double t = last_point->t + last_point->rate * std::chrono::duration<double>(s.time - last_point->at).count();
    std::lock_guard<std::mutex> lock(outcome.mutex);
    auto& r = outcome.last_read;
    const double dt = t - r.t;
    r.velocities.assign(s.positions.size(), 0.0);
    if (r.count > 0 && dt > 0 && r.positions.size() == s.positions.size())
      for (std::size_t j = 0; j < s.positions.size(); ++j) r.velocities[j] = (s.positions[j] - r.positions[j]) / dt;
    r.t = std::max(0.0, t);
    r.positions = s.positions;
    ++r.count;
  };
  // The runner: streamed, then every joint within its goal tolerance by
  // goal_time_tolerance after the end.
  arm::RunHooks hooks;
  hooks.executor = ctx.executor_options(eo);
  const double goal_time = tolerances.goal_time.value_or(defaults.goal_time);
  arm::WaitOptions w;
  w.timeout = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(goal_time));
  w.joint_tolerance = per_joint(tolerances.goal);
  hooks.wait = ctx.wait_options(w);
  bool late = false;
  hooks.not_arrived = [&](const Error& e) {
    late = true;
    return Error{e.kind, fmt::format("not within the goal tolerance {:.3f} s after the trajectory's end: {}", goal_time,
                                     e.message)};
  };
  auto report = arm::run_motion(arm, plan->plan, hooks);
  if (!report) {
    if (ctx.stopping()) {
      std::lock_guard<std::mutex> lock(outcome.mutex);
      outcome.stopped = true;
      return Ok{};
    }
    if (late) return fail(outcome, GoalError::goal_tolerance_violated, report.error());
    // A joint that fell behind or stalled (stopped, released), or an object put in the way
    // after the goal was accepted (the arm stopped before it): the path was not followed.
    const auto* contact = report.error().detail_as<arm::CollisionDetail>();
    const bool following = arm::following_error_of(report.error()) != nullptr || arm::stall_of(report.error()) != nullptr ||
                           (contact && contact->while_moving);
    return fail(outcome, following ? GoalError::path_tolerance_violated : GoalError::invalid_goal, report.error());
  }
  std::lock_guard<std::mutex> lock(outcome.mutex);
  if (report->last_motion) outcome.report = *report->last_motion;
  outcome.stopped = report->stopped || ctx.stopping();
  return Ok{};
}

}  // namespace armctl::ros_node

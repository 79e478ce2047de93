#include "ros/trajectory_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include <fmt/core.h>

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
  const auto& model = arm.model();
  auto now = arm.read();
  if (!now) return fail(outcome, GoalError::invalid_goal, now.error());
  ctx.positions(*now);
  auto plan = plan_trajectory(model, now->positions, request, defaults.start);
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
  auto report = arm::execute_motion(arm, plan->motion, ctx.executor_options(eo));
  if (!report) {
    const bool following = arm::following_error_of(report.error()) != nullptr;
    return fail(outcome, following ? GoalError::path_tolerance_violated : GoalError::invalid_goal, report.error());
  }
  {
    std::lock_guard<std::mutex> lock(outcome.mutex);
    outcome.report = *report;
    outcome.stopped = report->stopped;
  }
  if (report->stopped || ctx.stopping()) {
    std::lock_guard<std::mutex> lock(outcome.mutex);
    outcome.stopped = true;
    return Ok{};
  }

  // The end: every joint within its goal tolerance by goal_time_tolerance after the end.
  arm::WaitOptions w;
  const double goal_time = tolerances.goal_time.value_or(defaults.goal_time);
  w.timeout = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(goal_time));
  w.joint_tolerance = per_joint(tolerances.goal);
  auto arrived = arm.wait(ctx.wait_options(w));
  if (!arrived) {
    if (ctx.stopping()) {
      std::lock_guard<std::mutex> lock(outcome.mutex);
      outcome.stopped = true;
      return Ok{};
    }
    return fail(outcome, GoalError::goal_tolerance_violated,
                Error{arrived.error().kind,
                      fmt::format("not within the goal tolerance {:.3f} s after the trajectory's end: {}", goal_time,
                                  arrived.error().message)});
  }
  return Ok{};
}

}  // namespace armctl::ros_node

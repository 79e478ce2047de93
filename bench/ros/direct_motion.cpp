#include "direct_motion.hpp"

#include <algorithm>
#include <cmath>

#include "arm/motion_executor.hpp"
#include "ros/trajectory_goal.hpp"
#include "session/arm_session.hpp"

namespace armctl::ros_bench {

namespace {

std::unique_ptr<session::ArmSession> open(const std::string& arm) {
  session::SessionOptions o;
  o.wall_clock = true;
  return session::open_arm_session(arm, "", o).value();
}

}  // namespace

double direct_following_error(const std::string& arm, const ros_node::TrajectoryRequest& request) {
  auto s = open(arm);
  const auto& model = s->arm->model();
  const auto from = s->arm->read().value().positions;
  const auto plan = ros_node::plan_trajectory(model, from, request).value();
  const auto report = arm::execute_motion(*s->arm, plan.motion).value();
  double worst = 0;
  for (const auto& r : report.reads_log)
    for (int j = 0; j < model.chain_joints(); ++j)
      if (model.joints[std::size_t(j)].dimension == Dimension::angle)
        worst = std::max(worst, std::abs(r.planned[std::size_t(j)] - r.measured[std::size_t(j)]));
  return worst;
}

std::vector<double> start_positions(const std::string& arm) { return open(arm)->arm->read().value().positions; }

}  // namespace armctl::ros_bench

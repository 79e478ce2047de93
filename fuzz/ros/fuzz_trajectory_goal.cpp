// Trajectory goals as a ROS client may send them (ros/trajectory_goal.hpp) on hostile input,
// against the shipped xArm and SCARA models. The bytes give the arm, the joint names (a
// model name or garbage), the points (any doubles: NaN, infinities, huge) and tolerances.
// The checker must refuse with a GoalError code and a message, or return a plan that starts
// where the arm stands at rest, passes through every point, ends at rest and stays inside
// the position limits at the points.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "arm/arm_model.hpp"
#include "ros/trajectory_goal.hpp"

namespace {

using namespace armctl;

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_trajectory_goal: %s\n", what);
  std::abort();
}

const arm::ArmModel& model(int which) {
  static const arm::ArmModel xarm =
      arm::load_arm_model(std::string(ARMCTL_SOURCE_DIR) + "/config/xarm.arm.json").value();
  static const arm::ArmModel scara =
      arm::load_arm_model(std::string(ARMCTL_SOURCE_DIR) + "/config/scara.arm.json").value();
  return which ? scara : xarm;
}

struct Bytes {
  const std::uint8_t* data;
  std::size_t size, at = 0;
  std::uint8_t byte() { return at < size ? data[at++] : 0; }
  double number() {
    // Mostly small values around the joints' ranges, sometimes any 8 bytes.
    const std::uint8_t kind = byte();
    if (kind < 200) return (double(byte()) - 128) / 64.0 + (double(byte()) - 128) / 8192.0;
    double d = 0;
    std::uint8_t raw[8];
    for (auto& r : raw) r = byte();
    std::memcpy(&d, raw, sizeof d);
    return d;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in{data, size};
  const auto& m = model(in.byte() & 1);
  ros_node::TrajectoryRequest r;
  const int names = in.byte() % 10;
  for (int i = 0; i < names; ++i) {
    const std::uint8_t b = in.byte();
    if (b < 200) r.joint_names.push_back(m.joints[std::size_t(b) % m.joints.size()].name);
    else r.joint_names.push_back(std::string(1, char(b)));
  }
  const int points = in.byte() % 8;
  double t = 0;
  for (int k = 0; k < points; ++k) {
    ros_node::TrajectoryPoint p;
    const std::uint8_t step = in.byte();
    t = step < 240 ? t + step / 32.0 : in.number();
    p.time = t;
    const std::uint8_t shape = in.byte();
    const std::size_t n = shape < 230 ? r.joint_names.size() : shape % 10;
    for (std::size_t i = 0; i < n; ++i) p.positions.push_back(in.number());
    if (shape & 1) for (std::size_t i = 0; i < n; ++i) p.velocities.push_back(in.number() / 16);
    if (shape & 2) for (std::size_t i = 0; i < n; ++i) p.accelerations.push_back(in.number() / 16);
    if ((shape & 0x1c) == 0x1c) p.effort.push_back(1);
    r.points.push_back(std::move(p));
  }
  std::vector<double> from;
  for (const auto& j : m.joints) from.push_back(0.5 * (j.limits.lower + j.limits.upper));

  auto plan = ros_node::plan_trajectory(m, from, r);
  if (!plan) {
    const auto refusal = ros_node::refusal_of(plan.error());
    check(refusal.code == ros_node::GoalError::invalid_goal || refusal.code == ros_node::GoalError::invalid_joints,
          "a refusal with a goal's error code");
    check(!refusal.message.empty(), "a refusal says why");
  } else {
    std::vector<double> p, v, a;
    plan->motion.sample(0, p, v, a);
    for (std::size_t j = 0; j < p.size(); ++j) check(std::abs(p[j] - from[j]) < 0.03 && v[j] == 0, "starts at rest where the arm is");
    for (const auto& pt : r.points) {
      plan->motion.sample(pt.time, p, v, a);
      // A point at 0 s is where the arm stands (within the start tolerance): the plan starts there.
      const double slack = pt.time == 0 ? 0.021 : 0.0;
      for (std::size_t i = 0; i < pt.positions.size(); ++i)
        check(slack > 0 ? std::abs(p[std::size_t(plan->joints[i])] - pt.positions[i]) <= slack :
              std::abs(p[std::size_t(plan->joints[i])] - pt.positions[i]) < 1e-6 * (1 + std::abs(pt.positions[i])),
              "passes through every point");
      for (std::size_t j = 0; j < p.size(); ++j) check(m.joints[j].limits.contains(p[j], 1e-9), "inside the limits");
    }
    plan->motion.sample(plan->motion.duration, p, v, a);
    for (double x : v) check(std::abs(x) < 1e-9, "ends at rest");
  }
  std::vector<ros_node::JointTolerance> path, goal;
  for (const auto& n : r.joint_names) path.push_back({n, in.number()});
  if (!r.joint_names.empty()) goal.push_back({r.joint_names[0], in.number()});
  auto tol = ros_node::map_tolerances(m, r.joint_names, path, goal, in.number());
  if (tol) check(tol->path.size() == m.joints.size(), "a tolerance per joint");
  return 0;
}

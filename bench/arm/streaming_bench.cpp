// Host-planned motion on both simulated arms (issue "Motion", benchmark): a LIN move of the
// tool planned by arm::plan_path and streamed by the motion executor, at 9600 and 115200
// baud, on simulated time.
//  - path deviation: the largest distance of the real tool point (the simulators' own joint
//    positions after every stream point, through FK) from the ideal line, against the
//    quantization limit: the tool displacement of half a device unit on every chain joint
//    (servo units on the xArm, encoder clicks on the SCARA) at the middle of the line;
//  - end-pose error: where the tool comes to rest against the same limit;
//  - link use: the wire time of everything streamed (points and read-backs) over the
//    elapsed time: how close the stream runs to the link's floor.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/motion_executor.hpp"
#include "arm/motion_planning.hpp"
#include "arm/rc_arm_device.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "robot_commands/sim_links.hpp"

namespace {

using namespace armctl;

arm::ArmModel model(const char* name) { return arm::load_arm_model(arm::arm_file_path(name)).value(); }

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double f = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + f * d)).norm();
}

struct Result {
  double deviation = 0, end_error = 0, limit = 0, link_use = 0;
};

// Runs a LIN from where the arm stands by `offset` (m) at `speed` m/s; `true_joints` gives the
// simulator's own joint positions (SI) at any moment.
template <typename TrueJoints>
Result run_lin(arm::Arm& arm, const Eigen::Vector3d& offset, double speed, TrueJoints true_joints,
               Duration wire_per_point, Duration wire_per_read) {
  const auto start = arm.read().value().positions;
  const motion::Pose from = arm.forward(arm.chain_of(start));
  motion::PathSegment seg;
  seg.target = from;
  seg.target.position += offset;
  seg.speed = speed;
  const auto plan = arm::plan_path(arm.model(), start, std::span(&seg, 1));
  if (!plan) {
    std::fprintf(stderr, "bench_streaming: %s\n", plan.error().message.c_str());
    std::exit(1);
  }
  Result r;
  arm::ExecutorOptions o;
  o.on_point = [&](const arm::MotionProgress&) {
    const motion::Pose p = arm.forward(arm.chain_of(true_joints()));
    r.deviation = std::max(r.deviation, distance_to_segment(p.position, from.position, seg.target.position));
  };
  const auto report = arm::execute_motion(arm, plan->motion, o);
  if (!report) {
    std::fprintf(stderr, "bench_streaming: %s\n", report.error().message.c_str());
    std::exit(1);
  }
  (void)arm.wait();
  const motion::Pose end = arm.forward(arm.chain_of(true_joints()));
  r.end_error = (end.position - seg.target.position).norm();
  std::vector<double> middle = start;
  const auto& last = plan->checked->joints[plan->checked->joints.size() / 2];
  for (int i = 0; i < last.size(); ++i) middle[std::size_t(i)] = last[i];
  r.limit = arm::tool_quantization(arm.model(), arm.device().protocol(), middle);
  const double busy = std::chrono::duration<double>(wire_per_point * std::int64_t(report->points) +
                                                    wire_per_read * std::int64_t(report->reads))
                          .count();
  r.link_use = busy / std::chrono::duration<double>(report->elapsed).count();
  return r;
}

void print(const char* arm, unsigned baud, const Result& r) {
  std::printf("BENCH lin_path_deviation_%s_%u %.3f mm limit %.3f ratio %.2f\n", arm, baud, r.deviation * 1e3,
              2 * r.limit * 1e3, r.deviation / (2 * r.limit));
  std::printf("BENCH lin_end_error_%s_%u %.3f mm limit %.3f ratio %.2f\n", arm, baud, r.end_error * 1e3,
              2 * r.limit * 1e3, r.end_error / (2 * r.limit));
  std::printf("BENCH stream_link_use_%s_%u %.1f %% limit 90 ratio %.3f\n", arm, baud, r.link_use * 100,
              r.link_use / 0.9);
}

void run_xarm(std::uint32_t baud) {
  robot_commands::testing::EmulatedLink link(baud);
  robot_commands::Client client(link);
  arm::Arm arm(model("xarm"), std::make_unique<arm::RcArmDevice>(model("xarm"), client));
  // Start from a bent pose in front of the arm.
  std::vector<std::optional<double>> start{0.0, 0.5, 0.9, 0.6, 0.0, std::nullopt};
  arm::MoveOptions mo;
  (void)arm.move_joints(start, mo);
  (void)arm.wait();
  auto true_joints = [&] {
    std::vector<double> device;
    for (int id : {6, 5, 4, 3, 2, 1}) device.push_back(link.emulator().servos().commanded_position(std::uint8_t(id)));
    return arm.model().from_device(arm::Protocol::robot_commands, device);
  };
  const Duration point = arm.device().stream_period(false);
  const Duration read = arm.device().stream_period(true) - point;
  print("xarm", baud, run_lin(arm, {0, 0.08, 0}, 0.04, true_joints, point, read));
}

void run_scara(std::uint32_t baud) {
  auto c = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  c.baud = baud;
  joint_sim::SimArm sim(std::move(c));
  joint_bus::BusMaster master(sim.link());
  arm::Arm arm(model("scara"), std::make_unique<arm::BusArmDevice>(model("scara"), master, sim.link(), "simulated SCARA"));
  std::vector<std::optional<double>> start{0.15, 0.3, -0.8, 0.0, 0.0, 0.0, std::nullopt};
  (void)arm.move_joints(start);
  (void)arm.wait();
  auto true_joints = [&] {
    std::vector<double> device;
    for (const auto& j : arm.model().joints) device.push_back(sim.joint(j.map(arm::Protocol::joint_bus)->id).controller().position());
    return arm.model().from_device(arm::Protocol::joint_bus, device);
  };
  const Duration point = arm.device().stream_period(false);
  const Duration read = arm.device().stream_period(true) - point;
  print("scara", baud, run_lin(arm, {0, 0.1, 0}, 0.1, true_joints, point, read));
}

}  // namespace

int main() {
  for (std::uint32_t baud : {9600u, 115200u}) {
    run_xarm(baud);
    run_scara(baud);
  }
  return 0;
}

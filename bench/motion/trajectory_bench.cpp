// Calculation time of the trajectory generator (docs/trajectories.md): random cases for 1, 6
// and 7 joints, each from a random state inside the limits to a random target, limits
// spread over three decades (as in tests/motion/trajectory_random_cases.hpp). The mean is
// thread CPU time over the whole batch (the machine is shared: time spent preempted is not
// the generator's); the p99 is per call, wall clock, so it includes any preemption.
// Target: 7 joints in 5 us on average; the p99 against four times that.
// Then the 961 synchronized 7-joint cases of ../shared/vectors/trajectory-sync-7dof.json:
// the time per call and the fraction at Ruckig's optimal duration (within 1e-6 s; limit 1),
// and the cost of a waypoint section against a plain move (each section planned once).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "bench_report.hpp"
#include "../../tests/motion/trajectory_vectors.hpp"
#include "motion/trajectory.hpp"

namespace {

using namespace armctl::motion;

using armctl::bench::print;
using armctl::bench::thread_cpu_ns;

std::vector<TrajectoryInput> random_cases(int joints, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  };
  std::vector<TrajectoryInput> cases(count);
  for (auto& in : cases) {
    in.joints = joints;
    for (int i = 0; i < joints; ++i) {
      const double vmax = log_uniform(0.05, 50), amax = log_uniform(0.1, 100),
                   jmax = log_uniform(0.2, 1000);
      in.max_velocity[i] = vmax, in.max_acceleration[i] = amax, in.max_jerk[i] = jmax;
      in.position[i] = uniform(-5, 5);
      in.velocity[i] = uniform(-vmax, vmax);
      const double room = vmax - std::abs(in.velocity[i]);
      const double a_allowed = std::min(amax, 0.999999 * std::sqrt(2 * jmax * room));
      in.acceleration[i] = uniform(-a_allowed, a_allowed);
      const double reach = std::max(0.1, vmax * vmax / amax + vmax * amax / jmax);
      in.target_position[i] = in.position[i] + uniform(-3, 3) * std::min(reach, 10.0);
      in.target_velocity[i] = uniform(-vmax, vmax);
    }
  }
  return cases;
}

void bench_joints(int joints) {
  const int n = 20000;
  const auto cases = random_cases(joints, n, 42 + joints);
  Trajectory traj;
  // Warm up (and size `traj` once).
  for (int i = 0; i < 1000; ++i) benchmark::DoNotOptimize(calculate_trajectory(cases[i], traj));
  const double t0 = thread_cpu_ns();
  for (const auto& in : cases) benchmark::DoNotOptimize(calculate_trajectory(in, traj));
  const double mean_us = (thread_cpu_ns() - t0) / n / 1e3;
  std::vector<double> each(n);
  for (int i = 0; i < n; ++i) {
    const auto a = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(calculate_trajectory(cases[i], traj));
    each[i] =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - a).count();
  }
  std::nth_element(each.begin(), each.begin() + n * 99 / 100, each.end());
  const std::string name =
      "trajectory_" + std::to_string(joints) + (joints == 1 ? "_joint" : "_joints");
  print(name + "_mean", mean_us, "us", 5.0);
  print(name + "_p99", each[n * 99 / 100], "us", 20.0);
}

void bench_vectors() {
  using armctl::motion::testing::load_sync_vectors;
  const auto vectors = load_sync_vectors(std::string(ARMCTL_VECTORS_DIR) + "/trajectory-sync-7dof.json");
  Trajectory traj;
  int at_optimum = 0;
  for (const auto& v : vectors) {
    benchmark::DoNotOptimize(calculate_trajectory(v.in, traj));
    at_optimum += std::abs(traj.duration() - v.duration) <= 1e-6;
  }
  const int rounds = 20;
  const double t0 = thread_cpu_ns();
  for (int r = 0; r < rounds; ++r)
    for (const auto& v : vectors) benchmark::DoNotOptimize(calculate_trajectory(v.in, traj));
  const double mean_us = (thread_cpu_ns() - t0) / (rounds * double(vectors.size())) / 1e3;
  print("trajectory_vectors_7_joints_mean", mean_us, "us", 5.0);
  print("trajectory_vectors_at_optimum", double(at_optimum) / double(vectors.size()), "fraction",
        1.0);
}

// A waypoint section costs what a plain move costs: 7 joints through 3 waypoints (4 sections)
// against the 4 plain moves between the same states (the waypoint velocities the generator
// chooses), thread CPU time; limit 1.2 (each section planned twice was 1.8).
void bench_waypoints() {
  const int n = 5000;
  const auto starts = random_cases(7, 4 * n, 99);
  std::vector<TrajectoryInput> paths(n), moves(4 * std::size_t(n));
  std::vector<std::array<JointArray, 3>> waypoints(n);
  for (int c = 0; c < n; ++c) {
    TrajectoryInput in = starts[4 * std::size_t(c)];
    JointArray points[5];
    points[0] = in.position;
    for (int k = 1; k < 4; ++k) waypoints[c][k - 1] = points[k] = starts[4 * std::size_t(c) + k].position;
    points[4] = in.target_position;
    in.velocity = in.acceleration = in.target_velocity = JointArray{};
    in.waypoints = waypoints[c];
    paths[c] = in;
    JointArray velocities[5]{};
    waypoint_velocities(in, std::span<JointArray>(velocities + 1, 3));
    for (int k = 0; k < 4; ++k) {
      TrajectoryInput m = in;
      m.waypoints = {};
      m.position = points[k], m.target_position = points[k + 1];
      m.velocity = velocities[k], m.target_velocity = velocities[k + 1];
      moves[4 * std::size_t(c) + k] = m;
    }
  }
  Trajectory traj;
  for (int c = 0; c < 200; ++c) benchmark::DoNotOptimize(calculate_trajectory(paths[c], traj));
  double t0 = thread_cpu_ns();
  for (const auto& in : paths) benchmark::DoNotOptimize(calculate_trajectory(in, traj));
  const double path_ns = thread_cpu_ns() - t0;
  t0 = thread_cpu_ns();
  for (const auto& in : moves) benchmark::DoNotOptimize(calculate_trajectory(in, traj));
  const double moves_ns = thread_cpu_ns() - t0;
  print("trajectory_waypoint_section_vs_move", path_ns / moves_ns, "ratio", 1.2);
}

}  // namespace

int main() {
  for (int joints : {1, 6, 7}) bench_joints(joints);
  bench_vectors();
  bench_waypoints();
  return 0;
}

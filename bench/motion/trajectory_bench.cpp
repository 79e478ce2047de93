// Calculation time of the trajectory generator (docs/trajectories.md): random cases for 1, 6
// and 7 joints, each from a random state inside the limits to a random target, limits
// spread over three decades (as in tests/motion/trajectory_random_cases.hpp). The mean is
// thread CPU time over the whole batch (the machine is shared: time spent preempted is not
// the generator's); the p99 is per call, wall clock, so it includes any preemption.
// Target: 7 joints in 5 us on average; the p99 against four times that.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "motion/trajectory.hpp"

namespace {

using namespace armctl::motion;

double thread_cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e9 + double(t.tv_nsec);
}

void print(const std::string& name, double value, const char* unit, double limit) {
  std::printf("BENCH %s %.3f %s limit %.3f ratio %.3f\n", name.c_str(), value, unit, limit,
              value / limit);
}

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

}  // namespace

int main() {
  for (int joints : {1, 6, 7}) bench_joints(joints);
  return 0;
}

// The arm controller against its floors, on the simulated bus (simulated time, so the
// figures are the controller's and the bus's, not this machine's):
//  - joint-state refresh: sweeps of get_position over all seven joints per second under
//    continuous polling, against the wire-time floor (7 x 8 bytes x 10 bits / baud);
//  - latency the controller adds to an upstream request beyond wire time: a request that
//    arrives while the loop is in a bus step waits for the step to end (the runner looks at
//    the host between steps; a step waits at most a word time mid-transaction);
//    limit = one poll transaction's wire time.
// Plus the cost of the joint-bus planner the Arm API uses without a controller
// (joint_bus::plan_synchronized_move, BusArmDevice; Google Benchmark).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "devices/arm_controller/core_device.hpp"
#include "devices/joint_bus/sync_plan.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace {

using namespace armctl;
using namespace armctl::arm_controller;
using namespace armctl::joint_bus;  // the synchronized-move planner (devices/joint_bus/sync_plan.hpp)
using namespace std::chrono_literals;

struct Bench {
  explicit Bench(std::uint32_t baud) {
    auto c = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
    c.baud = baud;
    arm = std::make_unique<joint_sim::SimArm>(std::move(c));
    device = std::make_unique<CoreDevice>(arm->link(), load_controller_config(default_controller_config_path()),
                                          CoreDeviceOptions{}, [this](const rc::Frame&) { ++replies; });
  }
  std::unique_ptr<joint_sim::SimArm> arm;
  std::unique_ptr<CoreDevice> device;
  std::size_t replies = 0;
};

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

void refresh_rate(std::uint32_t baud) {
  Bench b(baud);
  const auto sweeps0 = b.device->core().stats().sweeps;
  const TimePoint t0 = b.device->clock().now();
  b.device->run_for(20s);
  const double rate = double(b.device->core().stats().sweeps - sweeps0) / seconds(b.device->clock().now() - t0);
  const double floor_rate = 1.0 / seconds(wire_time(8, baud) * 7);
  std::printf("BENCH arm_controller_refresh_%u %.3f sweeps/s limit %.3f ratio %.3f\n", baud, rate,
              floor_rate, rate / floor_rate);
}

void added_latency(std::uint32_t baud) {
  Bench b(baud);
  auto frame = *rc::encode(rc::Request{rc::ServoPositionRead{{1, 2, 3, 4, 5, 6, 7}}}, rc::ServoRange{1, 7});
  std::vector<double> waits;
  TimePoint arrival = b.device->clock().now();
  for (int i = 0; i < 2000; ++i) {
    // Arrivals spread over the transaction cycle (not a multiple of it).
    arrival += std::chrono::microseconds(3137 + (i * 7919) % 5000);
    // As ControllerRunner::run steps: at most 2 ms at a time, the host looked at between steps.
    while (b.device->clock().now() < arrival) b.device->step(b.device->clock().now() + 2ms);
    const TimePoint seen = b.device->clock().now();
    const auto before = b.replies;
    b.device->handle(frame);
    if (b.replies != before + 1) std::printf("no reply!\n");
    waits.push_back(seconds(seen - arrival) * 1e3);
  }
  std::sort(waits.begin(), waits.end());
  double mean = 0;
  for (double w : waits) mean += w;
  mean /= double(waits.size());
  const double limit = seconds(wire_time(8, baud)) * 1e3;
  std::printf("BENCH arm_controller_added_latency_mean_%u %.3f ms limit %.3f ratio %.3f\n", baud, mean, limit, mean / limit);
  const double p99 = waits[waits.size() * 99 / 100];
  std::printf("BENCH arm_controller_added_latency_p99_%u %.3f ms limit %.3f ratio %.3f\n", baud, p99, limit, p99 / limit);
}

void BM_PlanSevenJoints(benchmark::State& state) {
  std::vector<PlanInput> in;
  for (int j = 1; j <= 7; ++j) in.push_back({j, 1000.0 * j, {12000, 40000}, 20});
  for (auto _ : state) benchmark::DoNotOptimize(plan_synchronized_move(in, 2000ms, 20ms, 12ms));
}
BENCHMARK(BM_PlanSevenJoints);

}  // namespace

int main(int argc, char** argv) {
  for (std::uint32_t baud : {9600u, 115200u}) {
    refresh_rate(baud);
    added_latency(baud);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}

// Joint bus master on the simulated arm:
//  - sweep_get_position_<baud>: a get_position sweep over 7 joints; the wire-time floor
//    (8 bytes x 10 bits per joint) divided by the simulated bus time the sweep took.
//    1.0 = the master adds no gaps at all; limit 0.90.
//  - transaction_host_cpu_<baud>: host CPU time per transaction (master + simulated bus +
//    simulated joints together), in microseconds; limit = the transaction's own wire time
//    at that baud (a master slower than the wire could not keep the bus busy).
#include <chrono>
#include <cstdio>
#include <ctime>

#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_sim/sim_arm.hpp"

namespace {

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

int run(std::uint32_t baud) {
  auto config = armctl::joint_sim::load_arm_config(armctl::joint_sim::default_arm_config_path());
  config.baud = baud;
  armctl::joint_sim::SimArm arm(std::move(config));
  armctl::joint_bus::BusMaster master(arm.link());
  const armctl::Duration floor = armctl::wire_time(8 * 7, baud);

  constexpr int kSweeps = 200;
  armctl::Duration bus_time{0};
  int failures = 0;
  const double cpu0 = cpu_seconds();
  for (int s = 0; s < kSweeps; ++s) {
    const armctl::TimePoint t0 = arm.now();
    for (int j = 1; j <= 7; ++j) failures += master.get_position(j).ok() ? 0 : 1;
    bus_time += arm.now() - t0;
  }
  const double cpu = cpu_seconds() - cpu0;
  const double ratio = double(floor.count()) * kSweeps / double(bus_time.count());
  std::printf("BENCH sweep_get_position_%u %.4f ratio limit 0.90 ratio %.3f\n", baud, ratio, ratio / 0.90);
  const double us = cpu / (kSweeps * 7) * 1e6;
  const double limit_us = double(armctl::wire_time(8, baud).count()) / 1000.0;
  std::printf("BENCH transaction_host_cpu_%u %.2f us limit %.1f ratio %.3f\n", baud, us, limit_us, us / limit_us);
  if (failures) std::printf("bench_joint_bus: %d failed transactions\n", failures);
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main() { return run(9600) | run(115200); }

// Simulation speed of the whole simulated SCARA arm: 7 joints, each running the portable
// controller at 1 kHz with the motor model, driven over the simulated bus at 9600 baud.
// Figure: simulated seconds per wall-clock second (target >= 1000).
//   sim_speed_7_joints        every joint moving: a drive_to to each joint (by bus bytes)
//                             every 1.5 s, alternating +-3000 clicks, for 300 s simulated
//   sim_speed_7_joints_hold   every joint holding its position, no bus traffic
#include <chrono>
#include <cstdio>

#include "devices/joint_sim/sim_arm.hpp"
#include "portable/joint_bus_codes.hpp"

namespace {

using namespace armctl;
using namespace armctl::joint_sim;

// One transaction by bytes (no master library: keeps the benchmark about the simulator).
bool drive_to(transport::JointBusLink& link, int joint, std::int16_t position) {
  const Duration timeout = std::chrono::milliseconds(20);
  link.drain();
  link.set_select(joint, true);
  for (int i = 0; i < 2; ++i) {
    if (!link.read_byte(link.clock().now() + timeout)) return false;
  }
  const std::uint8_t bytes[4] = {
      joint_bus::word_low(joint_bus::cmd_drive_to), joint_bus::word_high(joint_bus::cmd_drive_to),
      joint_bus::word_low(position), joint_bus::word_high(position)};
  link.write(bytes);
  link.flush();
  link.set_select(joint, false);
  for (int i = 0; i < 2; ++i) {
    if (!link.read_byte(link.clock().now() + timeout)) return false;
  }
  return true;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void report(const char* name, double sim_s, double wall_s) {
  const double speed = sim_s / wall_s;
  std::printf("BENCH %s %.0f sim_s_per_wall_s limit 1000 ratio %.2f\n", name, speed,
              speed / 1000.0);
}

}  // namespace

int main() {
  {
    auto arm = SimArm::from_default_config();
    const auto t0 = std::chrono::steady_clock::now();
    std::int16_t target = 3000;
    std::uint64_t failures = 0;
    while (arm->now() < TimePoint{} + std::chrono::seconds(300)) {
      for (int j = 1; j <= 7; ++j) failures += drive_to(arm->link(), j, target) ? 0 : 1;
      arm->advance(std::chrono::milliseconds(1500));
      target = static_cast<std::int16_t>(-target);
    }
    const double wall = seconds_since(t0);
    const double simulated = std::chrono::duration<double>(arm->now().time_since_epoch()).count();
    std::printf("# moving: %.1f s simulated in %.3f s wall, %llu failed transactions\n",
                simulated, wall, static_cast<unsigned long long>(failures));
    report("sim_speed_7_joints", simulated, wall);
  }
  {
    auto arm = SimArm::from_default_config();
    const auto t0 = std::chrono::steady_clock::now();
    arm->advance(std::chrono::seconds(600));
    report("sim_speed_7_joints_hold", 600.0, seconds_since(t0));
  }
  return 0;
}

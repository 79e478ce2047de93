// The servo mode's host cost (docs/servo.md), on simulated time with a device that only
// records what it is sent (so that the figures are the loop's own, not a simulator's):
//  - servo_cycle_cpu_<arm>: thread CPU time per cycle while a twist is followed (the goals
//    from the tool Jacobian, the scaling, one synchronized generator step, the collision
//    check of the resting place), 7 joints on the SCARA; limit 20 us;
//  - servo_command_latency_<arm>: from a command to the stream call that carries it: a command
//    sent just after a cycle began waits one link period for the next cycle, then that cycle's
//    host time; the worst over 5,000 cycles, host time as the thread's CPU time (time the
//    machine gave to other processes is not the loop's), against one period plus 1 ms (the
//    issue's limit);
//  - servo_generator_step_7_joints: one ServoGenerator step for 7 joints with velocity goals,
//    thread CPU; limit 2 us.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <functional>
#include <string>
#include <vector>

#include "bench_report.hpp"
#include "arm/arm.hpp"
#include "arm/run_servo.hpp"
#include "motion/servo_generator.hpp"

namespace {

using namespace armctl;

using armctl::bench::print;
using armctl::bench::thread_cpu_ns;

// A device on simulated time that holds every joint where it was last sent (a perfect arm):
// what the loop costs, without a simulator's.
class RecordingDevice final : public arm::ArmDevice {
 public:
  RecordingDevice(const arm::ArmModel& model, std::vector<double> start, Duration period)
      : model_(model), at_(std::move(start)), period_(period) {}
  arm::Protocol protocol() const override { return arm::Protocol::robot_commands; }
  std::string description() const override { return "recording device"; }
  const Clock& clock() const override { return clock_; }
  Duration poll_interval() const override { return std::chrono::milliseconds(200); }
  Result<std::vector<double>> read_positions() override { return at_; }
  Status move(const std::vector<std::optional<double>>&, Duration) override { return Ok{}; }
  Status stop() override { return Ok{}; }
  Status set_torque(bool) override { return Ok{}; }
  Duration stream_period(bool with_read) const override { return with_read ? 2 * period_ : period_; }
  Duration stream_latency() const override { return period_; }
  Status stream(const std::vector<double>& targets, const std::vector<double>&, Duration) override {
    at_ = targets;
    ++points;
    if (on_stream) on_stream();
    return Ok{};
  }
  Status idle(Duration d) override {
    clock_.advance(d);
    return Ok{};
  }
  std::size_t points = 0;
  std::function<void()> on_stream;

 private:
  const arm::ArmModel& model_;
  SimClock clock_;
  std::vector<double> at_;
  Duration period_;
};

struct Figures {
  double cycle_cpu_us = 0, worst_latency_ms = 0, period_ms = 0;
};

// Follows a circling twist for `cycles` cycles from `start` (SI), a new command every cycle.
Figures run(const char* name, const std::vector<double>& start, int cycles) {
  arm::ArmModel model = arm::load_arm_model(arm::arm_file_path(name)).value();
  const auto period = std::chrono::microseconds(2170);  // the xArm's at 115200 baud
  auto device = std::make_unique<RecordingDevice>(model, model.to_device(arm::Protocol::robot_commands, start),
                                                  period);
  RecordingDevice& d = *device;
  arm::Arm a(model, std::move(device));
  arm::ServoInput input(a.model());
  int cycle = 0;
  double cpu_ns = 0, cpu_start = 0;
  double worst_host_ns = 0;
  arm::ServoOptions o;
  o.before_cycle = [&](TimePoint) {
    cpu_start = thread_cpu_ns();
    // A small circle in y and z, one turn in 2 s.
    const double phase = 2 * 3.14159265 * cycle * 0.00217 / 2;
    if (cycle < cycles) {
      (void)input.send(arm::ServoCommand{arm::ToolTwist{Eigen::Vector3d(0, 0.02 * std::cos(phase), 0.02 * std::sin(phase)),
                                                        Eigen::Vector3d::Zero(), arm::ServoFrame::base},
                                         std::nullopt});
    } else {
      input.finish();
    }
    ++cycle;
  };
  d.on_stream = [&] {
    const double host = thread_cpu_ns() - cpu_start;
    cpu_ns += host;
    worst_host_ns = std::max(worst_host_ns, host);
  };
  auto r = arm::run_servo(a, input, o);
  if (!r) {
    std::fprintf(stderr, "bench_servo: %s\n", r.error().message.c_str());
    std::exit(1);
  }
  Figures f;
  f.cycle_cpu_us = cpu_ns / double(d.points) / 1e3;
  f.period_ms = std::chrono::duration<double, std::milli>(r->period).count();
  // A command sent just after a cycle began waits a whole period for the next one, then
  // that cycle's host time until its point is handed to the link.
  f.worst_latency_ms = f.period_ms + worst_host_ns / 1e6;
  return f;
}

void bench_generator() {
  motion::ServoGenerator g;
  std::vector<motion::ServoJoint> joints(7, motion::ServoJoint{-3, 3, motion::JerkLimits{2, 10, 100}});
  std::vector<double> start(7, 0.0);
  (void)g.reset(joints, start);
  std::vector<motion::ServoGoal> goals(7);
  const int n = 200000;
  const double t0 = thread_cpu_ns();
  for (int k = 0; k < n; ++k) {
    const double v = (k / 500) % 2 ? 0.5 : -0.5;  // reversing every 500 steps: always changing
    for (int i = 0; i < 7; ++i) goals[std::size_t(i)] = {motion::ServoGoal::Kind::velocity, v * (1 + 0.1 * i)};
    g.step(goals, 0.002, true);
    benchmark::DoNotOptimize(g.position()[0]);
  }
  print("servo_generator_step_7_joints", (thread_cpu_ns() - t0) / n / 1e3, "us", 2.0);
}

}  // namespace

int main() {
  // The SCARA (7 joints) at a bent elbow; the xArm (6) bent in front.
  const Figures scara = run("scara", {0.15, 0.0, 1.0, 0.0, 0.0, 0.0, 0.02}, 5000);
  print("servo_cycle_cpu_scara_7_joints", scara.cycle_cpu_us, "us", 20.0);
  print("servo_command_latency_scara", scara.worst_latency_ms, "ms", scara.period_ms + 1.0);
  const Figures xarm = run("xarm", {0.0, 0.5, 1.0, 1.0, 0.0, 0.0}, 5000);
  print("servo_cycle_cpu_xarm_6_joints", xarm.cycle_cpu_us, "us", 20.0);
  print("servo_command_latency_xarm", xarm.worst_latency_ms, "ms", xarm.period_ms + 1.0);
  bench_generator();
  return 0;
}

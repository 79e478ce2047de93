// Leader and follower (`armctl follow`, jog/run_follow.hpp, docs/servo.md) on the embedded
// simulators on simulated time: an xArm on its emulated board (115200 baud) moved by hand
// leads an xArm, then the SCARA (its joint bus at 115200 baud).
//
//  - follow_latency_<leader>_to_<follower>: from the leader moved to the first byte of the
//    follower's command on its link, the worst over the session. The follow loop polls the
//    leader once per follower cycle (FollowRunOptions::leader_thread off, as on simulated
//    time); each arm's simulator has a clock of its own, so the two are put on one timeline:
//    the follower's, which a leader's read also advances by the time that read took on the
//    leader's link. A motion just after the board sampled the servos for one read (the
//    request's wire time after the read began) is seen by the next read, and commanded by
//    the next cycle's point: the latency is from that sample to that point's first byte
//    (when the follower's line is free), plus the host's CPU time meanwhile (the loop's:
//    not the simulators'; simulated time passes no host time). Limit: 1.5 times the two
//    links' floors, measured in the same run: the mean time of one position read on the
//    leader's link plus the wire time of one command on the follower's (the xArm: its
//    multi-servo frame; the SCARA: one transaction per joint).
//  - follow_tracking_<...>_largest / _mean: the follower's tool from where the mapping puts
//    the leader's (FollowReport, while the follower is neither slowed nor held) along a hand
//    motion. Limit: how far the leader's tool goes in 100 ms at the hand's fastest, a lag
//    that people driving an arm notice (the follower is jerk-limited: it cannot copy a hand's
//    start without some lag, and that lag is the figure).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "bench_report.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "jog/run_follow.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "robot_commands/sim_links.hpp"

namespace {

using namespace armctl;
using bench::print;
using bench::thread_cpu_ns;

double ms(Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

// CPU time spent in the simulators (a device's calls, the hand moving servos): not the host's.
struct SimulatorCpu {
  double ns = 0;
  template <class F>
  auto run(F&& f) {
    const double t0 = thread_cpu_ns();
    auto r = f();
    ns += thread_cpu_ns() - t0;
    return r;
  }
};

// A device passed through, timing what the follow loop does with it.
class TimedDevice final : public arm::ArmDevice {
 public:
  TimedDevice(std::unique_ptr<arm::ArmDevice> inner, SimulatorCpu& cpu) : inner_(std::move(inner)), cpu_(cpu) {}
  arm::Protocol protocol() const override { return inner_->protocol(); }
  std::string description() const override { return inner_->description(); }
  const Clock& clock() const override { return inner_->clock(); }
  Duration poll_interval() const override { return inner_->poll_interval(); }
  Result<std::vector<double>> read_positions() override {
    const TimePoint t0 = clock().now();
    auto r = cpu_.run([&] { return inner_->read_positions(); });
    if (on_read) on_read(clock().now() - t0);
    return r;
  }
  Status move(const std::vector<std::optional<double>>& t, Duration d) override {
    return cpu_.run([&] { return inner_->move(t, d); });
  }
  Status stop() override { return cpu_.run([&] { return inner_->stop(); }); }
  Status set_torque(bool on) override { return cpu_.run([&] { return inner_->set_torque(on); }); }
  Status release(int joint) override { return cpu_.run([&] { return inner_->release(joint); }); }
  Duration stream_period(bool with_read) const override { return inner_->stream_period(with_read); }
  Duration stream_latency() const override { return inner_->stream_latency(); }
  Status stream(const std::vector<double>& targets, const std::vector<double>& velocities, Duration in) override {
    // The command's first byte leaves when the line is free: a frame the link still sends
    // (the xArm's are sent without waiting for an answer) holds it for its wire time.
    const TimePoint first_byte = std::max(clock().now(), line_free_);
    if (on_stream) on_stream(first_byte);
    auto s = cpu_.run([&] { return inner_->stream(targets, velocities, in); });
    line_free_ = std::max(clock().now(), first_byte + inner_->stream_latency());
    return s;
  }
  Status idle(Duration d) override { return cpu_.run([&] { return inner_->idle(d); }); }

  std::function<void(Duration)> on_read;        // the read's time on this device's clock
  std::function<void(TimePoint)> on_stream;     // a command's first byte on this device's clock
  arm::ArmDevice& inner() { return *inner_; }

 private:
  std::unique_ptr<arm::ArmDevice> inner_;
  SimulatorCpu& cpu_;
  TimePoint line_free_{};
};

const arm::ArmModel& model(const std::string& name) {
  static const arm::ArmModel xarm = arm::load_arm_model(arm::arm_file_path("xarm")).value();
  static const arm::ArmModel scara = arm::load_arm_model(arm::arm_file_path("scara")).value();
  return name == "xarm" ? xarm : scara;
}

// The xArm on its emulated board at 115200 baud; a hand can move its servos (torque off).
struct Xarm {
  explicit Xarm(SimulatorCpu& cpu) {
    auto d = std::make_unique<TimedDevice>(std::make_unique<arm::RcArmDevice>(model("xarm"), client), cpu);
    device = d.get();
    arm = std::make_unique<arm::Arm>(model("xarm"), std::move(d));
  }
  void hand(int joint, double si) {
    const auto& map = *arm->model().joints[std::size_t(joint)].map(arm::Protocol::robot_commands);
    (void)link.emulator().servos().move_by_hand(std::uint8_t(map.id), std::round(map.to_device(si)));
  }
  robot_commands::testing::EmulatedLink link{115200};
  robot_commands::Client client{link};
  TimedDevice* device = nullptr;
  std::unique_ptr<arm::Arm> arm;
};

// The SCARA's simulated joints on their bus at 115200 baud.
struct Scara {
  explicit Scara(SimulatorCpu& cpu) {
    joint_sim::ArmConfig config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
    config.baud = 115200;
    sim = std::make_unique<joint_sim::SimArm>(std::move(config));
    master = std::make_unique<joint_bus::BusMaster>(sim->link());
    auto d = std::make_unique<TimedDevice>(
        std::make_unique<arm::BusArmDevice>(model("scara"), *master, sim->link(), "simulated SCARA"), cpu);
    device = d.get();
    arm = std::make_unique<arm::Arm>(model("scara"), std::move(d));
  }
  std::unique_ptr<joint_sim::SimArm> sim;
  std::unique_ptr<joint_bus::BusMaster> master;
  TimedDevice* device = nullptr;
  std::unique_ptr<arm::Arm> arm;
};

void bend(arm::Arm& a, std::vector<std::optional<double>> q) {
  if (!a.move_joints(q) || !a.wait()) {
    std::fprintf(stderr, "bench_follow: could not bend %s to its start\n", a.model().name.c_str());
    std::exit(1);
  }
}

// The hand's motion: from `from` by `by` over `seconds`, smoothly (half a cosine), then still.
std::vector<double> hand_at(const std::vector<double>& from, const std::vector<double>& by, double t, double seconds) {
  const double s = t >= seconds ? 1.0 : 0.5 - 0.5 * std::cos(std::numbers::pi * t / seconds);
  std::vector<double> q = from;
  for (std::size_t i = 0; i < q.size(); ++i) q[i] += s * by[i];
  return q;
}

struct Session {
  std::string name;          // "xarm_to_scara"
  std::vector<double> by;    // the hand's motion of the leader's joints (rad)
  double hand_seconds = 0;
};

void run(const Session& session, Xarm& leader, arm::Arm& follower, TimedDevice& follower_device, SimulatorCpu& cpu) {
  const auto from = leader.arm->read().value().positions;
  // The hand's fastest tool speed, for the tracking limit.
  double fastest = 0;
  const auto kinematics = leader.arm->kinematics();
  for (double t = 0; t < session.hand_seconds; t += 0.001) {
    const auto a = kinematics->pose_at(hand_at(from, session.by, t, session.hand_seconds)).position;
    const auto b = kinematics->pose_at(hand_at(from, session.by, t + 0.001, session.hand_seconds)).position;
    fastest = std::max(fastest, (b - a).norm() / 0.001);
  }

  // One timeline, the follower's clock: a leader's read lets its time pass there too.
  const std::size_t servos = leader.arm->model().joints.size();
  const Duration request = leader.link.frame_time(5 + servos);  // read positions: header, length, command, count, ids
  struct Cycle {
    TimePoint sample;             // when the leader's board sampled its servos (follower's clock)
    double cpu = 0, sim_cpu = 0;  // the thread's CPU and the simulators' at that read's end (ns)
  };
  std::optional<Cycle> previous;
  TimePoint read_began{};
  double cpu_at_read_end = 0, sim_at_read_end = 0;
  Duration read_total{0};
  std::size_t reads = 0;
  double worst_ms = 0, sum_ms = 0;
  std::vector<double> latencies;
  std::size_t points = 0;
  bool in_session = false;
  leader.device->on_read = [&](Duration took) {
    if (!in_session) return;
    read_began = follower.clock().now();
    (void)cpu.run([&] { return follower_device.inner().idle(took); });
    read_total += took;
    ++reads;
    cpu_at_read_end = thread_cpu_ns();
    sim_at_read_end = cpu.ns;
  };
  follower_device.on_stream = [&](TimePoint first_byte) {
    if (!in_session || reads == 0) return;
    if (previous) {
      // A motion just after the last cycle's sample is commanded by this point: the time
      // between on the timeline, and all the loop's CPU time since (the simulators' left out).
      const double host_ns = (thread_cpu_ns() - previous->cpu) - (cpu.ns - previous->sim_cpu);
      const double latency = ms(first_byte - previous->sample) + host_ns / 1e6;
      worst_ms = std::max(worst_ms, latency);
      sum_ms += latency;
      latencies.push_back(latency);
      ++points;
    }
    previous = Cycle{read_began + request, cpu_at_read_end, sim_at_read_end};
  };

  jog::FollowRunOptions o;
  o.leader_thread = false;
  std::optional<TimePoint> start;
  double t = 0;
  o.before_cycle = [&](TimePoint now) {
    in_session = true;
    if (!start) start = now;
    t = std::chrono::duration<double>(now - *start).count();
    const auto q = hand_at(from, session.by, t, session.hand_seconds);
    cpu.run([&] {
      for (int j = 0; j < 5; ++j) leader.hand(j, q[std::size_t(j)]);
      return 0;
    });
  };
  o.stop = [&] { return t >= session.hand_seconds + 0.5; };
  auto r = jog::run_follow(*leader.arm, follower, o);
  in_session = false;
  if (!r) {
    std::fprintf(stderr, "bench_follow %s: %s\n", session.name.c_str(), r.error().message.c_str());
    std::exit(1);
  }
  const double floor_ms = ms(read_total) / double(reads) + ms(follower_device.stream_period(false));
  print("follow_latency_" + session.name, worst_ms, "ms", 1.5 * floor_ms);
  print("follow_latency_" + session.name + "_mean", sum_ms / double(points), "ms", 1.5 * floor_ms);
  const double tracking_limit_mm = fastest * 0.1 * 1e3;
  print("follow_tracking_" + session.name + "_largest", r->largest_tracking_error * 1e3, "mm", tracking_limit_mm);
  print("follow_tracking_" + session.name + "_mean", r->mean_tracking_error * 1e3, "mm", tracking_limit_mm);
  const auto over = std::count_if(latencies.begin(), latencies.end(), [&](double l) { return l > 1.5 * floor_ms; });
  std::printf("  (%s: %zu points, %zd of them over the limit; floors: leader read %.3f ms + follower command %.3f ms; "
              "the hand's fastest %.0f mm/s)\n",
              session.name.c_str(), points, over, ms(read_total) / double(reads), ms(follower_device.stream_period(false)),
              fastest * 1e3);
}

}  // namespace

int main() {
  SimulatorCpu cpu;
  {
    // Five joints of an xArm moved together for 1.5 s: the follower copies them joint to joint.
    Xarm leader(cpu), follower(cpu);
    bend(*follower.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
    bend(*leader.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
    run({"xarm_to_xarm", {0.5, -0.2, 0.3, 0.0, 0.4, 0.0}, 1.5}, leader, *follower.arm, *follower.device, cpu);
  }
  {
    // The xArm's base turned and the arm lowered over 2 s: the SCARA's tool copies its tool.
    Xarm leader(cpu);
    Scara follower(cpu);
    bend(*leader.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
    bend(*follower.arm, {0.15, 0.0, 60 * std::numbers::pi / 180, std::nullopt, std::nullopt, std::nullopt,
                         std::nullopt});
    run({"xarm_to_scara", {0.3, 0.15, 0.0, 0.0, 0.0, 0.0}, 2.0}, leader, *follower.arm, *follower.device, cpu);
  }
  return 0;
}

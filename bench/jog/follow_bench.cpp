// Leader and follower (`armctl follow`, jog/run_follow.hpp, docs/servo.md) on the embedded
// simulators on simulated time: an xArm on its emulated board (115200 baud) moved by hand
// leads an xArm, then the SCARA (its joint bus at 115200 baud).
//
//  - follow_latency_<leader>_to_<follower>: from the leader moved to the first byte of the
//    follower's command on its link, the worst over the session, as `armctl follow` runs:
//    the leader read on a thread of its own, back to back on its link, while the follower's
//    loop takes the newest reading at each cycle. Each simulator has a clock of its own; the
//    bench puts them on one timeline, the follower's, and runs the leader's reads on it as
//    that thread would (run_follow polls the leader once per cycle, and the leader's device
//    catches up with the follower's clock: every read that would have ended by then, the
//    hand placed where it is at each). A motion just after the board sampled the servos for
//    one read (the request's wire time after the read began) is in the next reading: the
//    latency runs from that sample to the first byte of the first point that follows that
//    reading (when the follower's line is free), plus the host's CPU time since the
//    point before (the loop's, not the simulators': simulated time passes no host time).
//    Limit: 1.5 times the two links' floors, measured in the same run: the mean time of one
//    position read on the leader's link plus the wire time of one command on the
//    follower's (the xArm: its multi-servo frame; the SCARA: one transaction per joint).
//  - follow_latency_..._mean: the same, the mean over the readings.
//  - follow_latency_..._no_readback: the worst over the points that no read-back of the
//    follower (its following-error and stall checks, every few cycles) came before: how far
//    the rest of the chain is from the limit.
//  - follow_latency_..._one_thread: the leader read on the follower's thread instead, once
//    per cycle (the two links' times add up: the follower's own read-backs, every few
//    cycles, then stand between a sample and the point).
//  - follow_tracking_<...>_largest / _mean: the follower's tool from where the mapping puts
//    the leader's (FollowReport, while the follower is neither slowed nor held) along the
//    hand's motion, leader on its own thread. Limit: how far the leader's tool goes in
//    100 ms at the hand's fastest, a lag that people driving an arm notice (the follower is
//    jerk-limited: it cannot copy a hand's start without some lag, and that lag is the figure).
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
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "jog/run_follow.hpp"
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
    if (read_as) return read_as();
    return read_inner();
  }
  // One read of the device itself (or the reply to request_read); `took` its time on the
  // device's clock.
  Result<std::vector<double>> read_inner(Duration* took = nullptr) {
    if (!requested_) ++reads;
    requested_ = false;
    const TimePoint t0 = clock().now();
    auto r = cpu_.run([&] { return inner_->read_positions(); });
    if (took) *took = clock().now() - t0;
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
  // A read in two halves (the xArm's full-duplex line): the request holds the line after the
  // point before it; the reply comes back while the next point goes out.
  std::optional<Duration> read_request_time() const override { return inner_->read_request_time(); }
  // One joint at a time (the SCARA's half-duplex bus): each holds the bus for its read.
  std::optional<Duration> joint_read_time() const override { return inner_->joint_read_time(); }
  Result<double> read_joint(int joint) override {
    ++reads;
    return cpu_.run([&] { return inner_->read_joint(joint); });
  }
  Status request_read() override {
    ++reads;
    requested_ = true;
    line_free_ = std::max(clock().now(), line_free_) + *inner_->read_request_time();
    return cpu_.run([&] { return inner_->request_read(); });
  }

  std::function<Result<std::vector<double>>()> read_as;  // instead of a plain read
  std::function<void(TimePoint)> on_stream;  // a command's first byte on this device's clock
  std::size_t reads = 0;  // of the device itself (a follower's read-backs)
  arm::ArmDevice& inner() { return *inner_; }

 private:
  std::unique_ptr<arm::ArmDevice> inner_;
  SimulatorCpu& cpu_;
  TimePoint line_free_{};
  bool requested_ = false;  // a request_read's reply not yet taken
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

enum class LeaderReader { own_thread, one_thread };

struct Figures {
  double worst_ms = 0, mean_ms = 0, floor_ms = 0;
  // The worst over the points that no read-back of the follower's came before (since the
  // point before): what the latency is where the follower's own link does not hold it up.
  double worst_no_readback_ms = 0;
  std::size_t points = 0, over = 0;
  jog::FollowReport report;
};

// One session along the hand's motion from where both arms stand.
Figures run(const Session& session, LeaderReader reader, Xarm& leader, arm::Arm& follower,
            TimedDevice& follower_device, SimulatorCpu& cpu) {
  const auto from = leader.arm->read().value().positions;
  const std::size_t servos = leader.arm->model().joints.size();
  const Duration request = leader.link.frame_time(5 + servos);  // read positions: header, length, command, count, ids
  std::optional<TimePoint> start;  // the session's start on the timeline
  auto hand = [&](TimePoint at) {
    const auto q = hand_at(from, session.by, std::chrono::duration<double>(at - *start).count(), session.hand_seconds);
    cpu.run([&] {
      for (int j = 0; j < 5; ++j) leader.hand(j, q[std::size_t(j)]);
      return 0;
    });
  };

  // When each of the leader's readings was sampled, on the timeline.
  std::vector<TimePoint> readings;
  Duration read_total{0};
  Result<std::vector<double>> newest = leader.device->read_inner();
  TimePoint reader_free{};  // own thread: when its link is free for the next read
  Duration last_took{0};    // the last read's time (the next one takes as long)
  leader.device->read_as = [&]() -> Result<std::vector<double>> {
    const TimePoint now = follower.clock().now();
    if (!start) start = reader_free = now;
    auto read_at = [&](TimePoint began) {
      hand(began + request);
      Duration took{};
      newest = leader.device->read_inner(&took);
      read_total += took;
      last_took = took;
      readings.push_back(began + request);
      return took;
    };
    if (reader == LeaderReader::one_thread) {
      // The read's time passes on the follower's link too: one thread waits for both.
      const Duration took = read_at(now);
      (void)cpu.run([&] { return follower_device.inner().idle(took); });
      return newest;
    }
    // Every read the leader's thread would have finished by now, back to back.
    while (reader_free + last_took <= now) reader_free += read_at(reader_free);
    return newest;
  };

  // A motion just after the sample of the reading the previous point followed is first
  // followed by the point that takes a newer one.
  std::size_t followed = 0;  // readings taken by the points so far
  double cpu_at_point = thread_cpu_ns(), sim_at_point = cpu.ns;
  std::vector<double> latencies;
  std::vector<bool> behind_readback;  // per latency: a read-back since the point before
  std::size_t reads_at_point = follower_device.reads;
  follower_device.on_stream = [&](TimePoint first_byte) {
    if (!start) return;
    const double host_ns = (thread_cpu_ns() - cpu_at_point) - (cpu.ns - sim_at_point);
    cpu_at_point = thread_cpu_ns(), sim_at_point = cpu.ns;
    if (readings.size() > followed && followed > 0) {
      latencies.push_back(ms(first_byte - readings[followed - 1]) + host_ns / 1e6);
      behind_readback.push_back(follower_device.reads != reads_at_point);
    }
    reads_at_point = follower_device.reads;
    followed = readings.size();
  };

  jog::FollowRunOptions o;
  o.leader_thread = false;  // the bench runs the leader's reads on the timeline (read_as)
  double t = 0;
  o.before_cycle = [&](TimePoint now) {
    if (start) t = std::chrono::duration<double>(now - *start).count();
  };
  o.stop = [&] { return t >= session.hand_seconds + 0.5; };
  auto r = jog::run_follow(*leader.arm, follower, o);
  leader.device->read_as = nullptr;
  follower_device.on_stream = nullptr;
  if (!r) {
    std::fprintf(stderr, "bench_follow %s: %s\n", session.name.c_str(), r.error().message.c_str());
    std::exit(1);
  }
  Figures f;
  f.report = std::move(*r);
  f.floor_ms = ms(read_total) / double(readings.size()) + ms(follower_device.stream_period(false));
  f.points = latencies.size();
  for (std::size_t k = 0; k < latencies.size(); ++k) {
    const double l = latencies[k];
    if (!behind_readback[k]) f.worst_no_readback_ms = std::max(f.worst_no_readback_ms, l);
    f.worst_ms = std::max(f.worst_ms, l);
    f.mean_ms += l / double(latencies.size());
    f.over += l > 1.5 * f.floor_ms;
  }
  return f;
}

// Both arms from their start poses, the hand's motion once with each reader.
template <class MakeFollower>
void bench_session(const Session& session, std::vector<std::optional<double>> leader_start,
                   std::vector<std::optional<double>> follower_start, MakeFollower make_follower, SimulatorCpu& cpu) {
  Figures own, one;
  double fastest = 0;  // m/s: the leader's tool at the hand's fastest
  for (auto reader : {LeaderReader::own_thread, LeaderReader::one_thread}) {
    Xarm leader(cpu);
    auto follower = make_follower(cpu);
    bend(*leader.arm, leader_start);
    bend(*follower.arm, follower_start);
    const auto from = leader.arm->read().value().positions;
    const auto kinematics = leader.arm->kinematics();
    for (double t = 0; t < session.hand_seconds; t += 0.001) {
      const auto a = kinematics->pose_at(hand_at(from, session.by, t, session.hand_seconds)).position;
      const auto b = kinematics->pose_at(hand_at(from, session.by, t + 0.001, session.hand_seconds)).position;
      fastest = std::max(fastest, (b - a).norm() / 0.001);
    }
    (reader == LeaderReader::own_thread ? own : one) = run(session, reader, leader, *follower.arm, *follower.device, cpu);
  }
  const std::string name = "follow_latency_" + session.name;
  print(name, own.worst_ms, "ms", 1.5 * own.floor_ms);
  print(name + "_mean", own.mean_ms, "ms", 1.5 * own.floor_ms);
  print(name + "_no_readback", own.worst_no_readback_ms, "ms", 1.5 * own.floor_ms);
  print(name + "_one_thread", one.worst_ms, "ms", 1.5 * one.floor_ms);
  const double tracking_limit_mm = fastest * 0.1 * 1e3;
  print("follow_tracking_" + session.name + "_largest", own.report.largest_tracking_error * 1e3, "mm",
        tracking_limit_mm);
  print("follow_tracking_" + session.name + "_mean", own.report.mean_tracking_error * 1e3, "mm", tracking_limit_mm);
  std::printf("  (%s: floors %.3f ms; %zu readings followed, %zu over the limit; one thread: %zu, %zu over, mean "
              "%.3f ms; the hand's fastest %.0f mm/s)\n",
              session.name.c_str(), own.floor_ms, own.points, own.over, one.points, one.over, one.mean_ms,
              fastest * 1e3);
}

}  // namespace

int main() {
  SimulatorCpu cpu;
  const double deg = std::numbers::pi / 180;
  // Five joints of an xArm moved together for 1.5 s: the follower copies them joint to joint.
  bench_session({"xarm_to_xarm", {0.5, -0.2, 0.3, 0.0, 0.4, 0.0}, 1.5}, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt},
        {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt}, [](SimulatorCpu& c) { return Xarm(c); }, cpu);
  // The xArm's base turned and the arm lowered over 2 s: the SCARA's tool copies its tool.
  bench_session({"xarm_to_scara", {0.3, 0.15, 0.0, 0.0, 0.0, 0.0}, 2.0}, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt},
        {0.15, 0.0, 60 * deg, std::nullopt, std::nullopt, std::nullopt, std::nullopt},
        [](SimulatorCpu& c) { return Scara(c); }, cpu);
  return 0;
}

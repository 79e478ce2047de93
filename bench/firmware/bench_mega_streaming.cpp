// A streamed LIN on the SCARA through the Mega controller against the same LIN through the
// Linux daemon (issue 26, budget "a streamed LIN's path deviation on the emulated arm against
// the same figure through the daemon, <= 1.1x"). Both on the same emulated silicon: seven
// ATmega328P joints running the joint firmware with their simulated motors (AvrArm),
// judged by their emulated encoders.
//  - Mega: arm::Arm over RcArmDevice over the Robot Commands SDK over the Mega's UART0 (wire
//    timing) -> the Mega firmware on an emulated ATmega2560 -> the joint bus (AvrMegaArm).
//  - daemon: the same Arm/RcArmDevice/SDK over an in-process upstream link with the same
//    wire timing -> CoreDevice (the same core on Linux: what `armctl controller` and `armctl
//    sim scara --robot-commands` run) -> the same joints (AvrArm). Same code, the host's
//    timing: the figure says what emulated silicon costs the core.
// The LIN (100 mm at 100 mm/s, planned by arm::plan_path and streamed by the motion
// executor, as bench_streaming) is the same; path deviation = the largest distance of the
// tool (the joints' encoders through FK) from the ideal line, sampled after every stream
// point. Ratio = Mega / daemon, limit 1.1.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arm/arm.hpp"
#include "arm/motion_executor.hpp"
#include "arm/motion_planning.hpp"
#include "arm/rc_arm_device.hpp"
#include "devices/arm_controller/controller_config.hpp"
#include "devices/arm_controller/core_device.hpp"
#include "devices/joint_avr/avr_arm.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "devices/robot_commands/client.hpp"
#include "mega_rig.hpp"

namespace {

using namespace armctl;

// The daemon's upstream in process with the serial wire's timing at `baud`: a request
// reaches the controller when its last byte would have, a reply the host likewise (one
// direction at a time, back to back).
class DaemonRcLink final : public robot_commands::RcLink {
 public:
  explicit DaemonRcLink(std::uint32_t baud) : baud_(baud) {}
  void attach(arm_controller::CoreDevice& device) { device_ = &device; }
  void deliver(const rc::Frame& f) {
    const TimePoint begins = std::max(device_->clock().now(), up_free_);
    up_free_ = begins + frame_time(rc::encode_frame(f).size());
    inbox_.push_back({up_free_, f});
  }
  void send(const rc::Frame& frame) override {
    const TimePoint begins = std::max(device_->clock().now(), down_free_);
    down_free_ = begins + frame_time(rc::encode_frame(frame).size());
    outbox_.push_back({down_free_, frame});
  }
  std::optional<rc::Frame> receive(TimePoint deadline) override {
    for (;;) {
      const TimePoint now = device_->clock().now();
      while (!outbox_.empty() && outbox_.front().at <= now) {
        device_->handle(outbox_.front().frame);
        outbox_.pop_front();
      }
      if (!inbox_.empty() && inbox_.front().at <= now) {
        rc::Frame f = inbox_.front().frame;
        inbox_.pop_front();
        return f;
      }
      if (now >= deadline) return std::nullopt;
      TimePoint until = deadline;
      if (!outbox_.empty()) until = std::min(until, outbox_.front().at);
      if (!inbox_.empty()) until = std::min(until, inbox_.front().at);
      device_->step(std::max(until, now + std::chrono::microseconds(1)));
    }
  }
  const Clock& clock() const override { return device_->clock(); }
  std::string describe() const override { return "in-process daemon"; }
  Duration frame_time(std::size_t serial_bytes) const override { return wire_time(serial_bytes, baud_); }

 private:
  struct Timed {
    TimePoint at;
    rc::Frame frame;
  };
  std::uint32_t baud_;
  arm_controller::CoreDevice* device_ = nullptr;
  std::deque<Timed> outbox_, inbox_;
  TimePoint up_free_{}, down_free_{};
};

arm::ArmModel scara_model() { return arm::load_arm_model(arm::arm_file_path("scara")).value(); }

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double f = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + f * d)).norm();
}

struct LinResult {
  double deviation = 0, end_error = 0, following = 0, along_at_end = 0;
  std::size_t points = 0;
};

// Moves to the start pose, then streams the LIN; `clicks(joint)` = a joint's encoder.
template <typename Clicks>
LinResult run(arm::Arm& arm, Clicks clicks) {
  const std::vector<std::optional<double>> start_pose{0.15, 0.3, -0.8, 0.0, 0.0, 0.0, std::nullopt};
  if (!arm.move_joints(start_pose) || !arm.wait()) {
    std::fprintf(stderr, "bench_mega_streaming: the move to the start pose failed\n");
    std::exit(1);
  }
  auto true_joints = [&] {
    std::vector<double> device;
    for (const auto& j : arm.model().joints) device.push_back(double(clicks(j.map(arm::Protocol::joint_bus)->id)));
    return arm.model().from_device(arm::Protocol::joint_bus, device);
  };
  const auto start = arm.read().value().positions;
  const motion::Pose from = arm.forward(arm.chain_of(start));
  motion::PathSegment seg;
  seg.target = from;
  seg.target.position += Eigen::Vector3d(0, 0.1, 0);
  seg.speed = 0.1;
  const auto plan = arm::plan_path(arm.model(), start, std::span(&seg, 1));
  if (!plan) {
    std::fprintf(stderr, "bench_mega_streaming: %s\n", plan.error().message.c_str());
    std::exit(1);
  }
  LinResult r;
  arm::ExecutorOptions o;
  // The deviation is the figure: the executor's following-error halt (5 deg) is widened so
  // that a controller that lags is measured, not stopped.
  o.following_error_angle = 1.0;
  o.following_error_length = 0.2;
  const Eigen::Vector3d line = seg.target.position - from.position;
  o.on_point = [&](const arm::MotionProgress&) {
    const motion::Pose p = arm.forward(arm.chain_of(true_joints()));
    r.deviation = std::max(r.deviation, distance_to_segment(p.position, from.position, seg.target.position));
    r.along_at_end = (p.position - from.position).dot(line) / line.squaredNorm();
  };
  const auto report = arm::execute_motion(arm, plan->motion, o);
  if (!report) {
    std::fprintf(stderr, "bench_mega_streaming: %s\n", report.error().message.c_str());
    std::exit(1);
  }
  (void)arm.wait();
  r.points = report->points;
  r.following = report->largest_following_error;
  r.end_error = (arm.forward(arm.chain_of(true_joints())).position - seg.target.position).norm();
  return r;
}

robot_commands::ClientOptions client_options() {
  robot_commands::ClientOptions co;
  co.servo_count = 7;
  co.reply_timeout = std::chrono::milliseconds(500);
  return co;
}

// The Mega as the HIL tests run it (tests/hil/mega_rig.hpp: the SDK over its UART0 with
// wire timing, the emulation run while the SDK waits).
LinResult run_mega(std::uint32_t baud) {
  hil::MegaRig rig(baud);
  const arm::ArmModel model = scara_model();
  arm::Arm arm(model, std::make_unique<arm::RcArmDevice>(model, *rig.client));
  const LinResult r = run(arm, [&](int j) { return rig.clicks(j); });
  // A healthy arm: no joint was taken for one that stopped following (or stalled, which
  // would have stopped a move and spoilt the figure).
  int lost = 0;
  for (std::uint8_t servo = 1; servo <= 7; ++servo) {
    const auto faults = rig.client->read_joint_faults(servo);
    if (!faults || !*faults) {
      std::fprintf(stderr, "bench_mega_streaming: JointFaultRead of servo %d failed\n", servo);
      std::exit(1);
    }
    lost += (*faults)->following_lost;
  }
  std::printf("# %u Mega: joints that stopped following during the run: %d\n", baud, lost);
  return r;
}

// The Linux daemon: the same core on Linux (CoreDevice, what `armctl controller` runs).
LinResult run_daemon(std::uint32_t baud) {
  joint_avr::AvrArm joints(hil::hil_arm_config(baud));
  DaemonRcLink link(baud);
  arm_controller::CoreDevice device(
      joints.link(), arm_controller::load_controller_config(arm_controller::default_controller_config_path()), {},
      [&](const rc::Frame& f) { link.deliver(f); });
  link.attach(device);
  device.run_for(std::chrono::milliseconds(400));
  robot_commands::Client client(link, client_options());
  const arm::ArmModel model = scara_model();
  arm::Arm arm(model, std::make_unique<arm::RcArmDevice>(model, client));
  return run(arm, [&](int j) { return std::lround(joints.joint(j).hardware().position_clicks()); });
}

}  // namespace

int main() {
  for (const std::uint32_t baud : {9600u, 115200u}) {
    const LinResult mega = run_mega(baud);
    const LinResult daemon = run_daemon(baud);
    for (const auto& [who, r] : {std::pair{"Mega", mega}, std::pair{"daemon", daemon}}) {
      std::printf("# %u %s: path deviation %.3f mm, %.0f %% along the line at the last point, end error %.3f mm, "
                  "%zu points, largest joint following error %.2f deg\n",
                  baud, who, r.deviation * 1e3, r.along_at_end * 100, r.end_error * 1e3, r.points,
                  r.following * 57.2958);
    }
    std::printf("BENCH mega_lin_path_deviation_%u %.3f mm limit %.3f ratio %.3f\n", baud, mega.deviation * 1e3,
                1.1 * daemon.deviation * 1e3, mega.deviation / (1.1 * daemon.deviation));
  }
  return 0;
}

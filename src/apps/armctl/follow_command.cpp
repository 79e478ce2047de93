// armctl follow --leader ARM [--leader-device URI] --follower ARM [--follower-device URI]
//               [--joint-scale LIST] [--joint-offset LIST] [--tool-scale S] [--tool-offset X,Y,Z]
//               [--scene FILE] [--speed F] [--duration T] [--record FILE] [--record-rate R]
// The leader's torque off, moved by hand; the follower copies it through the servo mode
// (jog/run_follow.hpp, docs/servo.md). Ends on Enter, the end of input, Ctrl-C or after
// --duration, with the follower at rest and the leader's torque back on.
#include <chrono>
#include <cstdio>
#include <sstream>
#include <string>

#include <fmt/core.h>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/scene_option.hpp"
#include "apps/armctl/serve_support.hpp"
#include "apps/armctl/stdin_lines.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/quantity.hpp"
#include "files/recording_file.hpp"
#include "jog/run_follow.hpp"
#include "session/arm_session.hpp"

namespace armctl::cli {

namespace {

struct FollowArgs {
  std::string leader = "xarm", leader_device;
  std::string follower = "xarm", follower_device;
  std::string joint_scale, joint_offset, tool_offset;
  double tool_scale = 1;
  SceneArgs scene;  // --scene FILE, --fence, --reduced-mode
  double speed = 1;
  double duration = 0;  // s; 0: until Enter, the end of input or Ctrl-C
  std::string record;
  std::string record_rate = "50Hz";
};

[[noreturn]] void usage(const std::string& message) { throw ArmctlError(ErrorKind::invalid_argument, message); }

// "1,1,-1,1,1": numbers separated by commas.
std::vector<double> numbers(const std::string& text, const char* option) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      usage(fmt::format("{} '{}': numbers separated by commas, such as 1,1,-1,1,1", option, text));
    out.push_back(v);
  }
  return out;
}

// The leader's recording goes beside the follower's: session.rec -> session.leader.rec.
std::filesystem::path leader_file(const std::filesystem::path& record) {
  std::filesystem::path p = record;
  return p.replace_filename(record.stem().string() + ".leader" + record.extension().string());
}

void run_follow_command(const FollowArgs& a) {
  jog::FollowRunOptions o;
  if (!(a.speed > 0 && a.speed <= 1)) usage(fmt::format("--speed {}: above 0 up to 1", a.speed));
  if (!(a.duration >= 0 && a.duration <= 24 * 3600)) usage(fmt::format("--duration {}: 0 up to 86400 s", a.duration));
  if (!a.joint_scale.empty()) o.mapping.joint_scale = numbers(a.joint_scale, "--joint-scale");
  o.mapping.tool_scale = a.tool_scale;
  if (!a.tool_offset.empty()) {
    const auto v = numbers(a.tool_offset, "--tool-offset");
    if (v.size() != 3) usage(fmt::format("--tool-offset '{}': x,y,z in mm", a.tool_offset));
    o.mapping.tool_offset = Eigen::Vector3d(v[0], v[1], v[2]) / 1000;
  }
  if (!a.record.empty()) {
    auto rate = files::parse_rate(a.record_rate);
    if (!rate) usage("--record-rate: " + rate.error().message);
    o.record_rate = *rate;
    for (const auto& f : {std::filesystem::path(a.record), leader_file(a.record)})
      if (auto w = check_writable(f); !w) throw ArmctlError(w.error().kind, w.error().message + "; nothing moved");
  }
  // The leader is read in real time by a thread of its own, and the follower's loop times
  // the leader's silence (and --duration) on its own clock: an embedded SCARA simulator left
  // on simulated time would run ahead of the leader and find it lost. Both in step with the
  // wall clock, as real arms are.
  session::SessionOptions live;
  live.wall_clock = true;
  auto leader_session = session::open_arm_session(a.leader, a.leader_device, live).value();
  auto follower_session = session::open_arm_session(a.follower, a.follower_device, with_scene(a.scene, live)).value();
  arm::Arm& leader = *leader_session->arm;
  arm::Arm& follower = *follower_session->arm;
  if (!a.joint_offset.empty()) {
    // In the joints' own units, as people give them: degrees, millimetres.
    // Every value kept, so that a wrong count is refused by the mapping with the count it needs.
    const auto v = numbers(a.joint_offset, "--joint-offset");
    const auto& joints = follower.model().joints;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const bool length = i < joints.size() && joints[i].dimension == Dimension::length;
      o.mapping.joint_offset.push_back(length ? v[i] / 1000 : v[i] * M_PI / 180);
    }
  }
  o.servo.speed = a.speed;

  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);
  StdinLines input(interrupted.flag);
  const TimePoint started = follower.clock().now();
  // With --duration the input's end does not stop the session (a script may have none).
  o.stop = [&] {
    if (interrupted || input.line_ready()) return true;
    if (a.duration == 0) return input.ended();
    return follower.clock().now() - started >= std::chrono::duration<double>(a.duration);
  };
  TimePoint last_line{};
  o.on_cycle = [&](const jog::FollowStatus& s) {
    const TimePoint now = follower.clock().now();
    if (now - last_line < std::chrono::milliseconds(500)) return;
    last_line = now;
    const motion::Pose p = follower.kinematics()->pose_at(s.follower.positions);
    std::string line = fmt::format("follower tool x {:.1f} y {:.1f} z {:.1f} mm, {:.1f} mm from the leader's mapping",
                                   p.position.x() * 1000, p.position.y() * 1000, p.position.z() * 1000,
                                   s.tracking_error * 1000);
    if (!s.leader_lost.empty()) line += " | leader lost: " + s.leader_lost + " (the follower holds)";
    else if (s.follower.slowdown != arm::ServoSlowdown::none)
      line += fmt::format(" | slowed: {} {}", arm::to_string(s.follower.slowdown), s.follower.detail);
    fmt::print("{}\n", line);
    std::fflush(stdout);
  };
  fmt::print("leader '{}' on {}: torque off, move it by hand; follower '{}' on {} copies it ({}). Enter, the end of "
             "input or Ctrl-C ends.\n",
             leader.model().name, leader.device().description(), follower.model().name,
             follower.device().description(),
             leader.model().family == follower.model().family ? "joint to joint" : "tool to tool");
  std::fflush(stdout);
  auto r = jog::run_follow(leader, follower, o);
  if (!r) throw ArmctlError(r.error());
  if (!a.record.empty()) {
    for (auto* rec : {&r->follower_recording, &r->leader_recording})
      if (rec->samples.empty()) rec->samples.push_back({0, follower.read().value().positions});
    if (auto w = files::write_recording(a.record, r->follower_recording); !w) throw ArmctlError(w.error());
    if (auto w = files::write_recording(leader_file(a.record), r->leader_recording); !w) throw ArmctlError(w.error());
  }
  fmt::print("follower at rest, leader holding; {} leader readings, tracking error mean {:.1f} mm, largest {:.1f} mm{}\n",
             r->leader_reads, r->mean_tracking_error * 1000, r->largest_tracking_error * 1000,
             a.record.empty() ? "" : fmt::format("; written {} and {}", a.record, leader_file(a.record).string()));
}

}  // namespace

void add_follow_command(CLI::App& app) {
  auto a = std::make_shared<FollowArgs>();
  auto* cmd = app.add_subcommand(
      "follow", "Move a leader arm by hand and a follower arm copies it (docs/servo.md, \"Leader and follower\")");
  cmd->add_option("--leader", a->leader, "The leader arm: xarm, scara or an arm file (default xarm)");
  cmd->add_option("--leader-device", a->leader_device, "The leader's device URI (default: an embedded simulator)");
  cmd->add_option("--follower", a->follower, "The follower arm (default xarm)");
  cmd->add_option("--follower-device", a->follower_device, "The follower's device URI (default: an embedded simulator)");
  cmd->add_option("--joint-scale", a->joint_scale, "Same family: each follower joint = leader joint times this (1,1,-1,...)");
  cmd->add_option("--joint-offset", a->joint_offset, "Same family: plus this, per joint in deg or mm (0,10,0,...)");
  cmd->add_option("--tool-scale", a->tool_scale, "Different families: the tool's motion times this (default 1)");
  cmd->add_option("--tool-offset", a->tool_offset, "Different families: plus this, x,y,z in mm");
  add_scene_option(cmd, a->scene);
  cmd->add_option("--speed", a->speed, "Fraction of the follower's joint velocity limits (0..1, default 1)");
  cmd->add_option("--duration", a->duration, "Stop after this many seconds (default: Enter, end of input or Ctrl-C)");
  cmd->add_option("--record", a->record, "Write the session: FILE for the follower, FILE.leader beside it (recordings)");
  cmd->add_option("--record-rate", a->record_rate, "Samples a second in the recordings (default 50Hz)");
  cmd->callback([a] { run_follow_command(*a); });
}

}  // namespace armctl::cli

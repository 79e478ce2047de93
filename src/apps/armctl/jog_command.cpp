// armctl jog [--arm A] [--device URI] [--scene FILE] [--speed F]
// Drives the arm from the keyboard while keys are held (docs/servo.md): the keys become
// servo commands (jog/key_jog.hpp) that the servo mode follows (arm/run_servo.hpp), slowing
// near the ends of the joints' ranges, singularities and what the scene holds. A status line
// shows where the tool is and why it is slowed; space stops, Esc, x or Ctrl-C end the session
// with the arm at rest.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include <fmt/core.h>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/raw_terminal.hpp"
#include "apps/armctl/scene_option.hpp"
#include "apps/armctl/serve_support.hpp"
#include "arm/run_servo.hpp"
#include "core/error.hpp"
#include "jog/key_jog.hpp"
#include "session/arm_session.hpp"

namespace armctl::cli {

namespace {

struct JogArgs {
  std::string arm = "xarm";
  std::string device;
  std::string scene;
  double speed = 1.0;
};

// The tool's place and the session's state in one line.
std::string status_line(const arm::Arm& arm, const arm::ServoStatus& s, const jog::KeyJog& keys) {
  const motion::Pose p = arm.kinematics()->pose_at(s.positions);
  std::string line = fmt::format("x {:7.1f}  y {:7.1f}  z {:7.1f} mm | {}", p.position.x() * 1000,
                                 p.position.y() * 1000, p.position.z() * 1000, keys.describe());
  if (s.slowdown != arm::ServoSlowdown::none && s.slowdown != arm::ServoSlowdown::command_timeout)
    line += fmt::format(" | slowed: {}{}{}", arm::to_string(s.slowdown), s.detail.empty() ? "" : ": ", s.detail);
  return line;
}

void run_jog(const JogArgs& a) {
  if (!(a.speed > 0 && a.speed <= 1))
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("--speed {}: a fraction of the joints' velocity limits above 0 up to 1", a.speed));
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  arm::Arm& arm = *s->arm;
  jog::KeyJog keys(arm.model());
  arm::ServoInput input(arm.model());
  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);
  RawTerminal terminal;
  const bool live = isatty(STDOUT_FILENO);
  // In place on a terminal; as lines twice a second otherwise (a log, a test).
  auto say = [&](const std::string& text) {
    fmt::print("{}{}\n", live ? "\r\x1b[K" : "", text);
    std::fflush(stdout);
  };
  say(fmt::format("jogging arm '{}' on {}", arm.model().name, arm.device().description()));
  say(keys.help());
  say(keys.describe());

  arm::ServoOptions o;
  o.speed = a.speed;
  o.before_cycle = [&](TimePoint now) {
    for (const jog::Key& k : jog::decode_keys(terminal.read_available()))
      if (auto line = keys.press(k, now)) say(*line);
    // A pipe that ended ends the session once its last key is let go.
    if (keys.quit() || interrupted || (terminal.ended() && !keys.moving(now))) {
      input.finish();
      return;
    }
    (void)input.send(keys.command(now));  // built from the arm's own model: always valid
  };
  TimePoint last_line{};
  o.on_cycle = [&](const arm::ServoStatus& status) {
    const TimePoint now = arm.clock().now();
    if (now - last_line < (live ? std::chrono::milliseconds(100) : std::chrono::milliseconds(500))) return;
    last_line = now;
    const std::string line = status_line(arm, status, keys);
    if (live) {
      fmt::print("\r\x1b[K{}", line);
      std::fflush(stdout);
    } else {
      say(line);
    }
  };
  auto r = arm::run_servo(arm, input, o);
  if (live) fmt::print("\n");
  if (!r) throw ArmctlError(r.error());
  const motion::Pose p = arm.kinematics()->pose_at(r->positions);
  say(fmt::format("at rest at x {:.1f} y {:.1f} z {:.1f} mm after {:.1f} s ({} commands)", p.position.x() * 1000,
                  p.position.y() * 1000, p.position.z() * 1000, std::chrono::duration<double>(r->elapsed).count(),
                  r->commands));
}

}  // namespace

void add_jog_command(CLI::App& app) {
  auto a = std::make_shared<JogArgs>();
  auto* cmd = app.add_subcommand("jog", "Drive the arm from the keyboard while keys are held (docs/servo.md)");
  add_arm_options(cmd, a->arm, a->device);
  add_scene_option(cmd, a->scene);
  cmd->add_option("--speed", a->speed, "Fraction of every joint's velocity limit (0..1, default 1)");
  cmd->callback([a] { run_jog(*a); });
}

}  // namespace armctl::cli

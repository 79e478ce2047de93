#include "apps/armctl/jog_session.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>

#include <fmt/core.h>

#include "apps/armctl/serve_support.hpp"
#include "arm/run_servo.hpp"
#include "core/error.hpp"

namespace armctl::cli {
namespace {

// The tool's place and the session's state in one line.
std::string status_line(const arm::Arm& arm, const arm::ServoStatus& s, const JogDriver& driver) {
  const motion::Pose p = arm.kinematics()->pose_at(s.positions);
  std::string line = fmt::format("x {:7.1f}  y {:7.1f}  z {:7.1f} mm | {}", p.position.x() * 1000,
                                 p.position.y() * 1000, p.position.z() * 1000, driver.describe());
  if (s.slowdown != arm::ServoSlowdown::none && s.slowdown != arm::ServoSlowdown::command_timeout)
    line += fmt::format(" | slowed: {}{}{}", arm::to_string(s.slowdown), s.detail.empty() ? "" : ": ", s.detail);
  return line;
}

}  // namespace

void run_jog_session(arm::Arm& arm, JogDriver& driver, double speed) {
  if (!(speed > 0 && speed <= 1))
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("--speed {}: a fraction of the joints' velocity limits above 0 up to 1", speed));
  arm::ServoInput input(arm.model());
  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);
  const bool live = isatty(STDOUT_FILENO);
  // In place on a terminal; as lines twice a second otherwise (a log, a test).
  const Say say = [&](const std::string& text) {
    fmt::print("{}{}\n", live ? "\r\x1b[K" : "", text);
    std::fflush(stdout);
  };
  say(fmt::format("jogging arm '{}' on {}", arm.model().name, arm.device().description()));
  for (const std::string& line : driver.intro()) say(line);

  arm::ServoOptions o;
  o.speed = speed;
  o.before_cycle = [&](TimePoint now) {
    if (interrupted) input.finish();
    else driver.cycle(now, input, say);
  };
  TimePoint last_line{};
  o.on_cycle = [&](const arm::ServoStatus& status) {
    const TimePoint now = arm.clock().now();
    if (now - last_line < (live ? std::chrono::milliseconds(100) : std::chrono::milliseconds(500))) return;
    last_line = now;
    const std::string line = status_line(arm, status, driver);
    if (live) {
      fmt::print("\r\x1b[K{}", line);
      std::fflush(stdout);
    } else {
      say(line);
    }
  };
  auto r = arm::run_servo(arm, input, o);
  if (live) fmt::print("\n");
  driver.after(say);
  if (!r) throw ArmctlError(r.error());
  const motion::Pose p = arm.kinematics()->pose_at(r->positions);
  say(fmt::format("at rest at x {:.1f} y {:.1f} z {:.1f} mm after {:.1f} s ({} commands)", p.position.x() * 1000,
                  p.position.y() * 1000, p.position.z() * 1000, std::chrono::duration<double>(r->elapsed).count(),
                  r->commands));
}

}  // namespace armctl::cli

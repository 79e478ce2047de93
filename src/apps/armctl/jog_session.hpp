// One `armctl jog` session (docs/servo.md, docs/gamepad.md): the servo mode on the arm,
// driven by the keyboard or a gamepad, with the help, the status line (where the tool is,
// the settings, why it is slowed) and the line where it came to rest. The drivers differ
// only in where the commands come from.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "arm/arm.hpp"
#include "arm/servo_commands.hpp"
#include "core/clock.hpp"

namespace armctl::cli {

using Say = std::function<void(const std::string&)>;

class JogDriver {
 public:
  virtual ~JogDriver() = default;
  // The lines shown at the start (help, settings).
  virtual std::vector<std::string> intro() const = 0;
  // Once a cycle: read what arrived, then send this cycle's command or finish `input`.
  virtual void cycle(TimePoint now, arm::ServoInput& input, const Say& say) = 0;
  // The settings in words, for the status line.
  virtual std::string describe() const = 0;
  // Once the session is over, also when it failed: what the driver keeps (a recording).
  virtual void after(const Say&) {}
};

// Until the driver finishes the input (or SIGINT, SIGTERM) and the arm is at rest. `speed`:
// the fraction of the joints' velocity limits, checked here (0 < speed <= 1). Throws
// ArmctlError on the arm's errors.
void run_jog_session(arm::Arm& arm, JogDriver& driver, double speed);

}  // namespace armctl::cli

// Where a gamepad's events come from (docs/gamepad.md): a Linux evdev device
// (jog/evdev_gamepad.hpp) or a recorded stream replayed (jog/gamepad_replay.hpp), so that
// tests and demos drive the same mapping (jog/gamepad_jog.hpp) without a pad or uinput.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "jog/gamepad_jog.hpp"

namespace armctl::jog {

// What happened since the last poll, in the order it happened: the pad was opened
// (`connected`), its events, then maybe its loss (`unplugged`).
struct PadPoll {
  std::optional<PadDescription> connected;
  std::vector<PadEvent> events;
  bool unplugged = false;
  bool ended = false;  // a replay has nothing more to give (a device never ends)
};

class GamepadSource {
 public:
  virtual ~GamepadSource() = default;
  // Never waits. `now` is the session's clock: events are stamped with it.
  virtual PadPoll poll(TimePoint now) = 0;
  // "Microsoft X-Box 360 pad on /dev/input/event5", "the recording pad.txt".
  virtual std::string description() const = 0;
};

}  // namespace armctl::jog

#include "jog/gamepad_feed.hpp"

namespace armctl::jog {

std::vector<std::string> feed_gamepad(GamepadSource& source, GamepadJog& pad, arm::ServoInput& input,
                                      TimePoint now) {
  std::vector<std::string> lines;
  PadPoll p = source.poll(now);
  if (p.connected) {
    // A pad whose axes cannot be read stays unused (said once); the session waits on.
    auto line = pad.connect(*p.connected);
    lines.push_back(line ? *line : line.error().message);
  }
  for (const PadEvent& e : p.events)
    if (auto line = pad.event(e)) lines.push_back(std::move(*line));
  if (p.unplugged) lines.push_back(pad.unplug());
  // A replay ends after its last line; a device only with START held (or a signal).
  if (pad.quit(now) || p.ended) {
    if (pad.quit(now)) lines.emplace_back("stopping");
    input.finish();
    return lines;
  }
  (void)input.send(pad.command());  // built from the arm's own model: always valid
  return lines;
}

}  // namespace armctl::jog

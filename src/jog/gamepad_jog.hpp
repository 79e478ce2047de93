// Jogging from a gamepad (`armctl jog --gamepad`, docs/gamepad.md): the events a Linux
// evdev gamepad sends, turned into servo commands, as jog/key_jog.hpp does for keys. The
// common Xbox (xpad) and PlayStation (hid-sony, hid-playstation) layouts, told apart by the
// sticks' ranges and the device's name. Sticks and triggers have a dead zone of 10 % of
// their range, and motion grows linearly from its edge (no jump when a stick leaves it).
// Nothing moves unless the dead-man button (the left shoulder, LB / L1) is held; its
// release, a lost device or lost events stop the arm. Pure: events and times in, commands out.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "arm/arm_model.hpp"
#include "arm/servo_commands.hpp"
#include "core/clock.hpp"

namespace armctl::jog {

// One evdev event (struct input_event's type, code, value) and when it was read.
struct PadEvent {
  std::uint16_t type = 0, code = 0;
  std::int32_t value = 0;
  TimePoint time{};
};

// An absolute axis as the kernel reports it when the pad is opened (struct input_absinfo):
// its range, and its value then if known (else a stick is taken as centred, a trigger as
// released).
struct PadAxis {
  std::int32_t minimum = 0, maximum = 0;
  std::optional<std::int32_t> value;
};

// What a pad says about itself when it is opened.
struct PadDescription {
  std::string name;
  std::map<std::uint16_t, PadAxis> axes;  // by ABS_* code
};

enum class PadLayout { xbox, playstation };
const char* to_string(PadLayout layout);

// PlayStation when the name says so (Sony, PlayStation, DualShock, DualSense, "Wireless
// Controller") or when the left stick's range does not straddle 0 (hid-sony and
// hid-playstation report 0..255 centred at 128; xpad -32768..32767 centred at 0).
PadLayout layout_of(const PadDescription& pad);

// A stick's or trigger's value past the dead zone, as a fraction of its travel: 0 inside
// the dead zone, then linear from 0 at its edge to 1 at the end of the travel.
inline constexpr double kDeadZone = 0.1;
double past_dead_zone(double fraction);

class GamepadJog {
 public:
  explicit GamepadJog(const arm::ArmModel& model);

  // A pad was opened (at the start, or plugged in again). Errors (invalid_argument): an axis
  // whose minimum is not below its maximum. Everything held before is released: a pad
  // plugged in with the dead-man held still needs a fresh press.
  Result<std::string> connect(const PadDescription& pad);
  // The pad went away (unplugged, or its reads fail): the arm stops at once.
  std::string unplug();
  // One event. Axis changes take effect at the end of their frame (SYN_REPORT), as the
  // kernel groups them (a stick's x and y together); buttons at once. Lost events
  // (SYN_DROPPED) release the dead-man: the axes' values that follow are taken, buttons are
  // ignored until the frame ends, so motion needs a fresh dead-man press. Returns a line for
  // the user when a setting changed, else nothing.
  std::optional<std::string> event(const PadEvent& e);

  // The command for this cycle: the sticks' twist while the dead-man is held, a still one
  // otherwise (the arm slows to rest), with the gripper's last target.
  arm::ServoCommand command() const;
  bool connected() const { return pad_.has_value(); }
  bool deadman() const { return deadman_; }
  bool moving() const;
  // START held for kQuitHold ends the session (a brush against it does not).
  bool quit(TimePoint now) const { return start_held_since_ && now - *start_held_since_ >= kQuitHold; }
  static constexpr Duration kQuitHold = std::chrono::seconds(1);

  arm::ServoFrame frame() const { return frame_; }
  int speed_step() const { return speed_step_; }
  std::string help() const;
  std::string describe() const;

 private:
  // Every axis as a fraction past its dead zone, -1..1 (triggers 0..1), signed as the tool
  // moves: stick pushed forward or left is +.
  double axis(std::uint16_t code) const;
  std::optional<std::string> button(std::uint16_t code, bool pressed, TimePoint time);
  void release_all();

  const arm::ArmModel& model_;
  std::optional<PadDescription> pad_;
  PadLayout layout_ = PadLayout::xbox;
  std::map<std::uint16_t, std::int32_t> values_, pending_;  // by ABS_* code
  bool deadman_ = false;
  arm::ServoFrame frame_ = arm::ServoFrame::base;
  int speed_step_;
  std::optional<double> gripper_;
  std::optional<TimePoint> start_held_since_;
  bool dropped_ = false;  // SYN_DROPPED seen: events ignored until the next SYN_REPORT
};

}  // namespace armctl::jog

// Jogging from a keyboard (`armctl jog`, docs/servo.md): the keys a terminal sends, turned
// into servo commands. A terminal reports presses only, repeated while a key is held (after
// a first delay of a quarter to two thirds of a second, then some 30 times a second): a
// motion key counts as held from its press until its repeats stop, and as one short nudge
// when it does not repeat. Pure: keys and times in, commands out.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "arm/arm_model.hpp"
#include "arm/servo_commands.hpp"
#include "core/clock.hpp"
#include "jog/jog_speeds.hpp"

namespace armctl::jog {

// One key as a terminal sends it.
struct Key {
  enum class Kind { character, up, down, left, right, page_up, page_down, escape, interrupt };
  Kind kind = Kind::character;
  char character = 0;  // for Kind::character
  bool operator==(const Key&) const = default;
};

// The keys in `bytes` as a terminal in raw mode sends them: arrows and page keys as escape
// sequences (ESC [ A .. ESC [ D, ESC [ 5 ~, ESC [ 6 ~), a lone ESC as escape, Ctrl-C as
// interrupt. Unknown sequences are dropped whole.
std::vector<Key> decode_keys(std::string_view bytes);

enum class JogMode { tool, joint };

// What the keys steer, and how fast.
struct JogState {
  JogMode mode = JogMode::tool;
  arm::ServoFrame frame = arm::ServoFrame::base;
  int speed_step = kStartSpeedStep;  // index into the speed steps (jog/jog_speeds.hpp)
  int joint = 0;       // the joint moved in joint mode
};

class KeyJog {
 public:
  explicit KeyJog(const arm::ArmModel& model);

  // A key pressed at `now`. Returns a line for the user when a setting changed or help was
  // asked ("speed 50 mm/s, 40 deg/s"), else nothing.
  std::optional<std::string> press(const Key& key, TimePoint now);
  // The command for this cycle: the held motion key's twist or joint velocity, a still one
  // when none is held (the arm slows to rest), with the gripper's last target.
  arm::ServoCommand command(TimePoint now);
  bool moving(TimePoint now) const { return held_ && now < held_until_; }
  bool quit() const { return quit_; }
  const JogState& state() const { return state_; }
  // One line: every key and what it does.
  std::string help() const;
  // The settings in words: "tool moves in the base frame at 25 mm/s, 20 deg/s".
  std::string describe() const;

  // A key counts as held this long after its press, and after each repeat once it repeats.
  static constexpr Duration kFirstHold = std::chrono::milliseconds(700);
  static constexpr Duration kRepeatHold = std::chrono::milliseconds(120);

 private:
  // The motion a key asks for: a unit direction of the twist, or of the joint.
  struct Motion {
    Eigen::Vector3d linear = Eigen::Vector3d::Zero(), angular = Eigen::Vector3d::Zero();
    double joint = 0;  // +1 / -1 in joint mode
  };
  std::optional<Motion> motion_of(const Key& key) const;
  std::optional<std::string> setting(const Key& key);

  const arm::ArmModel& model_;
  JogState state_;
  std::optional<Motion> held_;
  Key held_key_{};
  TimePoint held_until_{};
  bool repeating_ = false;
  std::optional<double> gripper_;
  bool quit_ = false;
};

}  // namespace armctl::jog

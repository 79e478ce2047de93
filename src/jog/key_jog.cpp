#include "jog/key_jog.hpp"

#include <array>
#include <numbers>

#include <fmt/format.h>

#include "arm/arm_kinematics.hpp"
#include "jog/jog_speeds.hpp"

namespace armctl::jog {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

Key character(char c) { return Key{Key::Kind::character, c}; }

}  // namespace

std::vector<Key> decode_keys(std::string_view bytes) {
  std::vector<Key> keys;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const char c = bytes[i];
    if (c == 3) {
      keys.push_back({Key::Kind::interrupt, 0});
    } else if (c == 27) {
      if (i + 1 >= bytes.size() || (bytes[i + 1] != '[' && bytes[i + 1] != 'O')) {
        keys.push_back({Key::Kind::escape, 0});
        continue;
      }
      // ESC [ then parameters (digits, ';') and one final byte.
      std::size_t j = i + 2;
      while (j < bytes.size() && ((bytes[j] >= '0' && bytes[j] <= '9') || bytes[j] == ';')) ++j;
      if (j >= bytes.size()) break;  // cut off: dropped
      const std::string_view params = bytes.substr(i + 2, j - i - 2);
      switch (bytes[j]) {
        case 'A': keys.push_back({Key::Kind::up, 0}); break;
        case 'B': keys.push_back({Key::Kind::down, 0}); break;
        case 'C': keys.push_back({Key::Kind::right, 0}); break;
        case 'D': keys.push_back({Key::Kind::left, 0}); break;
        case '~':
          if (params == "5") keys.push_back({Key::Kind::page_up, 0});
          if (params == "6") keys.push_back({Key::Kind::page_down, 0});
          break;
        default: break;
      }
      i = j;
    } else if (c >= 32 && c < 127) {
      keys.push_back(character(c));
    }
  }
  return keys;
}

KeyJog::KeyJog(const arm::ArmModel& model) : model_(model) {}

std::optional<KeyJog::Motion> KeyJog::motion_of(const Key& key) const {
  Motion m;
  char c = key.kind == Key::Kind::character ? key.character : 0;
  // Arrows and page keys stand for w s a d r f.
  switch (key.kind) {
    case Key::Kind::up: c = 'w'; break;
    case Key::Kind::down: c = 's'; break;
    case Key::Kind::left: c = 'a'; break;
    case Key::Kind::right: c = 'd'; break;
    case Key::Kind::page_up: c = 'r'; break;
    case Key::Kind::page_down: c = 'f'; break;
    default: break;
  }
  if (state_.mode == JogMode::joint) {
    if (c == 'w') m.joint = 1;
    else if (c == 's') m.joint = -1;
    else return std::nullopt;
    return m;
  }
  switch (c) {
    case 'w': m.linear = Eigen::Vector3d::UnitX(); break;
    case 's': m.linear = -Eigen::Vector3d::UnitX(); break;
    case 'a': m.linear = Eigen::Vector3d::UnitY(); break;
    case 'd': m.linear = -Eigen::Vector3d::UnitY(); break;
    case 'r': m.linear = Eigen::Vector3d::UnitZ(); break;
    case 'f': m.linear = -Eigen::Vector3d::UnitZ(); break;
    case 'j': m.angular = Eigen::Vector3d::UnitX(); break;
    case 'l': m.angular = -Eigen::Vector3d::UnitX(); break;
    case 'i': m.angular = Eigen::Vector3d::UnitY(); break;
    case 'k': m.angular = -Eigen::Vector3d::UnitY(); break;
    case 'q': m.angular = Eigen::Vector3d::UnitZ(); break;
    case 'e': m.angular = -Eigen::Vector3d::UnitZ(); break;
    default: return std::nullopt;
  }
  return m;
}

std::optional<std::string> KeyJog::setting(const Key& key) {
  if (key.kind == Key::Kind::escape || key.kind == Key::Kind::interrupt) {
    quit_ = true;
    held_.reset();
    return "stopping";
  }
  if (key.kind != Key::Kind::character) return std::nullopt;
  const char c = key.character;
  const int chain = model_.chain_joints();
  if (c == ' ') {
    held_.reset();
    return "stop";
  }
  if (c == 'x') {
    quit_ = true;
    held_.reset();
    return "stopping";
  }
  if (c == 'h' || c == '?') return help();
  if (c == '+' || c == '=' || c == ']' || c == '-' || c == '_' || c == '[') {
    const bool up = c == '+' || c == '=' || c == ']';
    state_.speed_step = std::clamp(state_.speed_step + (up ? 1 : -1), 0, kSpeedSteps - 1);
    return describe();
  }
  if (c == 'm') {
    state_.mode = state_.mode == JogMode::tool ? JogMode::joint : JogMode::tool;
    held_.reset();
    return describe();
  }
  if (c == 't') {
    state_.frame = state_.frame == arm::ServoFrame::base ? arm::ServoFrame::tool : arm::ServoFrame::base;
    state_.mode = JogMode::tool;
    held_.reset();
    return describe();
  }
  if (c >= '1' && c <= '9') {
    const int j = c - '1';
    if (j >= chain) return fmt::format("no joint {}: arm '{}' has joints 1..{}", j + 1, model_.name, chain);
    state_.joint = j;
    state_.mode = JogMode::joint;
    held_.reset();
    return describe();
  }
  if (state_.mode == JogMode::joint && (c == 'a' || c == 'd')) {
    state_.joint = (state_.joint + (c == 'd' ? 1 : chain - 1)) % chain;
    return describe();
  }
  if (c == 'o' || c == 'c') {
    if (!model_.gripper) return fmt::format("arm '{}' has no gripper", model_.name);
    gripper_ = c == 'c' ? 1.0 : 0.0;
    return c == 'c' ? "gripper closing" : "gripper opening";
  }
  return std::nullopt;
}

std::optional<std::string> KeyJog::press(const Key& key, TimePoint now) {
  // Left and right select joints in joint mode rather than moving.
  const bool selects = state_.mode == JogMode::joint &&
                       (key.kind == Key::Kind::left || key.kind == Key::Kind::right);
  if (auto m = selects ? std::nullopt : motion_of(key)) {
    // The same key again while held is its repeat: from then on it is held only as long as
    // repeats keep coming.
    const bool repeat = held_ && held_key_ == key && now < held_until_;
    repeating_ = repeat;
    held_ = m;
    held_key_ = key;
    held_until_ = now + (repeat ? kRepeatHold : kFirstHold);
    return std::nullopt;
  }
  if (selects) return setting(character(key.kind == Key::Kind::right ? 'd' : 'a'));
  return setting(key);
}

arm::ServoCommand KeyJog::command(TimePoint now) {
  arm::ServoCommand c;
  c.gripper = gripper_;
  if (!moving(now)) {
    held_.reset();
    c.motion = arm::ToolTwist{};
    return c;
  }
  const int step = state_.speed_step;
  if (state_.mode == JogMode::joint) {
    std::vector<double> v(std::size_t(model_.joint_count()), 0.0);
    const auto& limits = model_.joints[std::size_t(state_.joint)].limits;
    v[std::size_t(state_.joint)] = held_->joint * kJointFractionSteps[std::size_t(step)] * limits.velocity;
    c.motion = arm::JointVelocities{std::move(v)};
    return c;
  }
  c.motion = arm::ToolTwist{held_->linear * kLinearSteps[std::size_t(step)] / 1000,
                            held_->angular * kAngularSteps[std::size_t(step)] * kDeg, state_.frame};
  return c;
}

std::string KeyJog::describe() const {
  const std::size_t step = std::size_t(state_.speed_step);
  if (state_.mode == JogMode::joint) {
    const auto& j = model_.joints[std::size_t(state_.joint)];
    return fmt::format("joint {} ({}) at {:g} % of its velocity limit", state_.joint + 1, j.name,
                       kJointFractionSteps[step] * 100);
  }
  return fmt::format("tool moves in the {} frame at {:g} mm/s, {:g} deg/s", arm::to_string(state_.frame),
                     kLinearSteps[step], kAngularSteps[step]);
}

std::string KeyJog::help() const {
  return "keys: w/s x+/-  a/d y+/-  r/f z+/-  (arrows, PgUp/PgDn)  j/l roll  i/k pitch  q/e yaw  | "
         "t base/tool frame  m tool/joint mode  1-7 joint  +/- speed  o/c gripper  | "
         "space stop  Esc or x quit  h help";
}

}  // namespace armctl::jog

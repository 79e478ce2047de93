#include "jog/gamepad_jog.hpp"

#include <libevdev/libevdev.h>
#include <linux/input-event-codes.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/printable.hpp"
#include "jog/jog_speeds.hpp"

namespace armctl::jog {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

bool is_trigger(std::uint16_t code) { return code == ABS_Z || code == ABS_RZ; }

std::string axis_name(std::uint16_t code) {
  const char* name = libevdev_event_code_get_name(EV_ABS, code);
  return name ? name : std::to_string(code);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The pads' buttons by where they sit. xpad reports X (left) as BTN_X and Y (top) as BTN_Y,
// the same codes as BTN_NORTH and BTN_WEST; hid-sony and hid-playstation follow the
// kernel's gamepad spec (Triangle BTN_NORTH, Square BTN_WEST).
std::uint16_t top_button(PadLayout layout) { return layout == PadLayout::xbox ? BTN_Y : BTN_NORTH; }

}  // namespace

const char* to_string(PadLayout layout) { return layout == PadLayout::xbox ? "Xbox" : "PlayStation"; }

PadLayout layout_of(const PadDescription& pad) {
  const std::string name = lower(pad.name);
  for (const char* word : {"sony", "playstation", "dualshock", "dualsense", "wireless controller"})
    if (name.find(word) != std::string::npos) return PadLayout::playstation;
  auto x = pad.axes.find(ABS_X);
  if (x != pad.axes.end() && x->second.minimum >= 0) return PadLayout::playstation;
  return PadLayout::xbox;
}

double past_dead_zone(double fraction) {
  const double a = std::min(std::abs(fraction), 1.0);
  if (a <= kDeadZone) return 0;
  return std::copysign((a - kDeadZone) / (1 - kDeadZone), fraction);
}

GamepadJog::GamepadJog(const arm::ArmModel& model) : model_(model), speed_step_(kStartSpeedStep) {}

Result<std::string> GamepadJog::connect(const PadDescription& pad) {
  for (const auto& [code, a] : pad.axes)
    if (!(a.minimum < a.maximum))
      return Error{ErrorKind::invalid_argument,
                   fmt::format("gamepad '{}': axis {} has range {}..{}; the minimum must be below the maximum",
                               printable(pad.name), axis_name(code), a.minimum, a.maximum)};
  release_all();
  dropped_ = false;
  pad_ = pad;
  layout_ = layout_of(pad);
  values_.clear();
  for (const auto& [code, a] : pad.axes)
    values_[code] = a.value.value_or(
        is_trigger(code) ? a.minimum : std::int32_t((std::int64_t(a.minimum) + a.maximum) / 2));
  return fmt::format("gamepad '{}' ({} layout): hold {} to move", printable(pad.name), to_string(layout_),
                     layout_ == PadLayout::xbox ? "LB" : "L1");
}

std::string GamepadJog::unplug() {
  release_all();
  pad_.reset();
  return "gamepad lost: stopping; waiting for a gamepad";
}

void GamepadJog::release_all() {
  deadman_ = false;
  start_held_since_.reset();
  pending_.clear();
}

double GamepadJog::axis(std::uint16_t code) const {
  if (!pad_) return 0;
  auto range = pad_->axes.find(code);
  auto v = values_.find(code);
  if (range == pad_->axes.end() || v == values_.end()) return 0;
  const double lo = range->second.minimum, hi = range->second.maximum;
  if (is_trigger(code)) return past_dead_zone(std::clamp((v->second - lo) / (hi - lo), 0.0, 1.0));
  return past_dead_zone(std::clamp((v->second - (lo + hi) / 2) / ((hi - lo) / 2), -1.0, 1.0));
}

std::optional<std::string> GamepadJog::event(const PadEvent& e) {
  if (!pad_) return std::nullopt;
  if (e.type == EV_SYN && e.code == SYN_DROPPED) {
    release_all();
    dropped_ = true;
    return "gamepad events lost: stopping; press the dead-man again";
  }
  if (e.type == EV_SYN && e.code == SYN_REPORT) {
    dropped_ = false;
    std::optional<std::string> line;
    for (const auto& [code, value] : pending_) {
      // The d-pad's up and down step the speed once per press.
      if (code == ABS_HAT0Y && value != 0 && value != values_[code]) {
        speed_step_ = std::clamp(speed_step_ + (value < 0 ? 1 : -1), 0, kSpeedSteps - 1);
        line = describe();
      }
      values_[code] = value;
    }
    pending_.clear();
    return line;
  }
  if (e.type == EV_ABS) {
    if (pad_->axes.contains(e.code)) pending_[e.code] = e.value;
    return std::nullopt;
  }
  // Key repeats (value 2) change nothing; buttons during lost events are ignored.
  if (e.type == EV_KEY && e.value != 2 && !dropped_) return button(e.code, e.value != 0, e.time);
  return std::nullopt;
}

std::optional<std::string> GamepadJog::button(std::uint16_t code, bool pressed, TimePoint time) {
  if (code == BTN_TL) {
    deadman_ = pressed;
    return std::nullopt;
  }
  if (code == BTN_START) {
    if (pressed) start_held_since_ = time;
    else start_held_since_.reset();
    return pressed ? std::optional<std::string>("hold START for a second to end the session") : std::nullopt;
  }
  if (!pressed) return std::nullopt;
  if (code == BTN_SOUTH || code == BTN_EAST) {
    if (!model_.gripper) return fmt::format("arm '{}' has no gripper", model_.name);
    gripper_ = code == BTN_SOUTH ? 1.0 : 0.0;
    return code == BTN_SOUTH ? "gripper closing" : "gripper opening";
  }
  if (code == top_button(layout_)) {
    frame_ = frame_ == arm::ServoFrame::base ? arm::ServoFrame::tool : arm::ServoFrame::base;
    return describe();
  }
  if (code == BTN_SELECT) return help();
  return std::nullopt;
}

bool GamepadJog::moving() const {
  if (!deadman_) return false;
  for (std::uint16_t code : {ABS_X, ABS_Y, ABS_RX, ABS_RY, ABS_Z, ABS_RZ, ABS_HAT0X})
    if (axis(code) != 0) return true;
  return false;
}

arm::ServoCommand GamepadJog::command() const {
  arm::ServoCommand c;
  c.gripper = gripper_;
  if (!deadman_) return c;  // a still twist: the arm slows to rest
  // The sticks' forward and left are +x and +y (evdev's y grows downward, x to the right);
  // the right trigger raises, the left lowers; the right stick turns about z (left +) and
  // pitches (forward +); the d-pad (-1, 0, 1) rolls (left +) at full speed.
  const Eigen::Vector3d linear(-axis(ABS_Y), -axis(ABS_X), axis(ABS_RZ) - axis(ABS_Z));
  const Eigen::Vector3d angular(-axis(ABS_HAT0X), -axis(ABS_RY), -axis(ABS_RX));
  const std::size_t step = std::size_t(speed_step_);
  c.motion = arm::ToolTwist{linear * kLinearSteps[step] / 1000, angular * kAngularSteps[step] * kDeg, frame_};
  return c;
}

std::string GamepadJog::describe() const {
  const std::size_t step = std::size_t(speed_step_);
  return fmt::format("tool moves in the {} frame at up to {:g} mm/s, {:g} deg/s", arm::to_string(frame_),
                     kLinearSteps[step], kAngularSteps[step]);
}

std::string GamepadJog::help() const {
  const bool x = layout_ == PadLayout::xbox;
  return fmt::format(
      "gamepad: hold {} to move | left stick x/y  {} z up/down  right stick yaw/pitch  d-pad left/right roll | "
      "d-pad up/down speed  {} base/tool frame  {} close / {} open gripper | {} help  START held 1 s quits",
      x ? "LB" : "L1", x ? "RT/LT" : "R2/L2", x ? "Y" : "Triangle", x ? "A" : "Cross", x ? "B" : "Circle",
      x ? "Back" : "Share");
}

}  // namespace armctl::jog

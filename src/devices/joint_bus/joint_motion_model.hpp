// What the controller knows about each joint's setpoint: a copy of the joint's own setpoint
// ramp (portable/setpoint_ramp, the same fixed-point arithmetic the joint runs every 1 ms
// tick), fed with every target and speed the controller has successfully sent, at the
// instant each took effect. The joint bus has no velocity read, and differentiating polled
// positions (one reading per joint per sweep, 58 ms apart at 9600 baud) would be late and
// noisy; the controller commanded the motion, so it can replay it exactly (to within one
// tick of phase). A move that starts while a joint is moving is planned from this state.
//
// The model is "unknown" until the first poll, while the position loop is off, and after a
// command to the joint failed (it may or may not have taken effect); then the planner falls
// back to the polled position at rest.
#pragma once

#include <cstdint>
#include <optional>

#include "core/clock.hpp"
#include "devices/joint_bus/sync_plan.hpp"
#include "portable/setpoint_ramp.hpp"

namespace armctl::joint_bus {

class JointMotionModel {
 public:
  // `configured`: the joint's velocity at 100 % and acceleration, as in the arm config.
  explicit JointMotionModel(const JointProfile& configured);

  bool known() const { return known_; }
  void forget() {
    known_ = false;
    percent_.reset();
  }
  // The speed percentage last set (nothing if none was set since the model was lost).
  std::optional<int> speed_percent() const { return percent_; }
  // The setpoint is at rest on `clicks`, and so is the target (start-up, loop turned on).
  void rest_at(std::int32_t clicks, TimePoint t);
  // Commands, applied at the instant they took effect (ignored while unknown).
  void drive_to(std::int16_t clicks, TimePoint t);
  void set_speed(int percent, TimePoint t);

  // The ramp as it will be at `t` (>= the last command) if nothing else is sent; `tick`
  // gets the instant of the last tick it has made by then.
  joint_bus::SetpointRamp ramp_at(TimePoint t, TimePoint* tick = nullptr) const;
  std::int32_t target_q8() const { return target_q8_; }
  // At rest on its target at `t`: a new move can be planned as rest to rest.
  bool settled_at(TimePoint t) const;
  double setpoint_clicks_at(TimePoint t) const;

 private:
  void advance(TimePoint t);  // run the ticks up to t

  joint_bus::SetpointRamp ramp_;
  std::int32_t target_q8_ = 0;
  TimePoint last_tick_{};  // the model's ticks fall on last_tick_ + k ms
  bool known_ = false;
  std::optional<int> percent_;
};

}  // namespace armctl::joint_bus

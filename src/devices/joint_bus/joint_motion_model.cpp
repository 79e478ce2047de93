#include "devices/joint_bus/joint_motion_model.hpp"

#include <chrono>

#include "portable/fixed_point.hpp"

namespace armctl::joint_bus {

namespace {
constexpr Duration kTick = std::chrono::milliseconds(1);
}  // namespace

JointMotionModel::JointMotionModel(const JointProfile& configured) {
  // Converted as the joint converts them (portable/fixed_point.hpp).
  const auto top = static_cast<std::uint32_t>(configured.max_speed_cps);
  const auto accel = static_cast<std::uint32_t>(configured.max_accel_cps2);
  ramp_.configure(static_cast<std::int32_t>(speed_q8_per_tick(top)), static_cast<std::int32_t>(accel_q8_per_tick2(accel)));
}

void JointMotionModel::rest_at(std::int32_t clicks, TimePoint t) {
  ramp_.reset(clicks * 256);
  target_q8_ = clicks * 256;
  last_tick_ = t;
  known_ = true;
}

void JointMotionModel::advance(TimePoint t) {
  // At rest on the target nothing changes: skip the idle ticks, keeping the tick phase.
  while (last_tick_ + kTick <= t) {
    if (ramp_.velocity_q8() == 0 && ramp_.setpoint_q8() == target_q8_) {
      last_tick_ += ((t - last_tick_) / kTick) * kTick;
      return;
    }
    ramp_.step(target_q8_);
    last_tick_ += kTick;
  }
}

void JointMotionModel::drive_to(std::int16_t clicks, TimePoint t) {
  if (!known_) return;
  advance(t);
  target_q8_ = std::int32_t{clicks} * 256;
}

void JointMotionModel::set_speed(int percent, TimePoint t) {
  if (!known_) return;
  advance(t);
  ramp_.set_speed_percent(static_cast<std::uint8_t>(percent));
  percent_ = percent;
}

joint_bus::SetpointRamp JointMotionModel::ramp_at(TimePoint t, TimePoint* tick) const {
  JointMotionModel copy = *this;
  copy.advance(t);
  if (tick) *tick = copy.last_tick_;
  return copy.ramp_;
}

bool JointMotionModel::settled_at(TimePoint t) const {
  const joint_bus::SetpointRamp r = ramp_at(t);
  return r.velocity_q8() == 0 && r.setpoint_q8() == target_q8_;
}

double JointMotionModel::setpoint_clicks_at(TimePoint t) const { return ramp_at(t).setpoint_q8() / 256.0; }

}  // namespace armctl::joint_bus

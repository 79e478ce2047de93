// How fast a planned motion moves the tool point: reduced mode's cap on the tool speed is
// kept by the planner (arm/plan_moves.hpp) with it, and tests measure plans with it.
#pragma once

#include "arm/arm_kinematics.hpp"
#include "arm/motion_executor.hpp"

namespace armctl::arm {

// Sampled every this much of the motion's nominal time (at most kMaxToolSpeedSamples).
inline constexpr double kToolSpeedStep = 0.002;  // s
inline constexpr int kMaxToolSpeedSamples = 20000;

// The largest speed of the tool point (m/s) along `motion` at 100 %: the Jacobian times the
// chain joints' velocities at every sample.
double peak_tool_speed(const ArmKinematics& kinematics, const PlannedMotion& motion);

}  // namespace armctl::arm

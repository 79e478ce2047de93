// Planning one synchronized move (MultiServoMove): every joint named reaches its target at
// the same instant, `wanted` after the move starts.
//
// Method (docs/arm-controller.md, "Synchronization"): each joint runs its own trapezoidal
// profile (velocity limit = set_speed %, acceleration limit = its tuning), so one drive_to
// per joint is enough and the bus stays free for polling. For each joint the planner picks
// the smallest whole percentage whose rest-to-rest time fits, then delays that joint's
// drive_to so that it ends exactly at the common instant: the start delay absorbs both the
// 1 % quantization of set_speed and the serialization of commands on the bus (one joint
// per transaction). Drive commands are spaced at least one transaction apart so none has
// to wait for another. Pure computation: no I/O, no clock.
#pragma once

#include <span>
#include <vector>

#include "core/clock.hpp"

namespace armctl::arm_controller {

struct JointProfile {
  double max_speed_cps = 1;   // at set_speed 100 %
  double max_accel_cps2 = 1;
};

// What the joint really does with these settings: the joint controller works in Q8 clicks
// per 1 ms tick, so both limits are quantized (mirrors portable/position_loop.cpp).
JointProfile as_quantized_by_joint(JointProfile p);

// Seconds for a rest-to-rest move of `distance` clicks (>= 0) at `percent` (1..100) of
// the profile's top speed.
double move_seconds(double distance, int percent, const JointProfile& profile);

struct PlanInput {
  int joint = 0;
  double distance = 0;  // clicks, absolute
  JointProfile profile;
  double zone = 0;      // clicks: the joint counts as arrived this close to its target
};

// A joint must not creep through its zone: the planner never picks a speed at which the
// last `zone` clicks take longer than this (else a slow joint "arrives" early).
inline constexpr Duration kZoneCrossing = std::chrono::milliseconds(20);

struct PlannedJoint {
  int joint = 0;
  int percent = 100;     // set_speed for this move
  Duration start{};      // drive_to takes effect this long after the move starts
  Duration duration{};   // the joint's own profile time
};

struct SyncPlan {
  Duration total{};  // >= wanted: every joint arrives this long after the start
  std::vector<PlannedJoint> joints;  // in the order given
};

// `setup`: bus time before the first drive_to can take effect (speed commands etc.);
// `transaction`: bus time of one drive_to, the spacing between drive commands.
SyncPlan plan_synchronized_move(std::span<const PlanInput> inputs, Duration wanted, Duration setup,
                                Duration transaction);

}  // namespace armctl::arm_controller

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

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/clock.hpp"
#include "portable/setpoint_ramp.hpp"

namespace armctl::joint_bus {

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

// A joint that is not at rest on its target when the move starts (still moving, or held
// short of it by set_speed 0): its setpoint ramp as the controller's model predicts it
// (joint_motion_model.hpp), `at` after the move's start, heading for `old_target_q8`.
struct MovingStart {
  joint_bus::SetpointRamp ramp;
  std::int32_t old_target_q8 = 0;
  Duration at{};
};

struct PlanInput {
  int joint = 0;
  double distance = 0;  // clicks, absolute (from the setpoint now)
  JointProfile profile;
  double zone = 0;      // clicks: the joint counts as arrived this close to its target
  // Moving start: planned by running the joint's own ramp arithmetic forward (exact, 1 ms
  // ticks) instead of the rest-to-rest formula; then `target_q8` is the new target.
  std::optional<MovingStart> moving{};
  std::int32_t target_q8 = 0;
};

// A joint must not creep through its zone: the planner never picks a speed at which the
// last `zone` clicks take longer than this (else a slow joint "arrives" early).
inline constexpr Duration kZoneCrossing = std::chrono::milliseconds(20);

struct PlannedJoint {
  int joint = 0;
  int percent = 100;     // set_speed for this move
  Duration start{};      // drive_to takes effect this long after the move starts
  Duration duration{};   // the joint's own profile time
  // Moving start: drive_to goes first and set_speed after it (a speed change first would
  // push the joint on toward its old target; the new target first makes it turn or brake
  // at once; the moving joints' drive_to's all go before their set_speed's), and the 1 % quantization of set_speed is absorbed by
  // switching to `switch_percent` (one percent slower) at `switch_at`, since delaying the
  // drive_to of a moving joint would let it run on toward the old target.
  bool drive_first = false;
  Duration speed_at{};  // drive_first: when its set_speed takes effect
  std::optional<int> switch_percent{};
  Duration switch_at{};
};

struct SyncPlan {
  Duration total{};  // >= wanted: every joint arrives this long after the start
  std::vector<PlannedJoint> joints;  // in the order given
};

// When a moving joint's setpoint comes to rest on `target_q8` (offset from the move's
// start), if it gets drive_to at `drive`, set_speed `percent` at `speed`, and optionally
// set_speed `switch_percent` at `switch_at`; nothing if that is later than `give_up`.
std::optional<Duration> moving_arrival(const MovingStart& start, std::int32_t target_q8, Duration drive,
                                       Duration speed, int percent, std::optional<int> switch_percent,
                                       Duration switch_at, Duration give_up);

// `setup`: bus time before the first drive_to can take effect (speed commands etc.);
// `transaction`: bus time of one drive_to, the spacing between drive commands (a speed
// command and a drive command: each joint's pair of commands fills one such slot).
SyncPlan plan_synchronized_move(std::span<const PlanInput> inputs, Duration wanted, Duration setup,
                                Duration transaction);

}  // namespace armctl::joint_bus

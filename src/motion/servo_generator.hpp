// The servo generator: steers every joint, one short cycle at a time, toward what a stream of
// commands asks now (a velocity, or a position to go to), from the state it reached in the
// last cycle, within the joint's velocity, acceleration and jerk limits and its position
// range (docs/servo.md). The core of jogging, teleoperation and leader/follower.
//
// Each cycle is planned anew from the current state with the jerk-limited generator:
// - a velocity goal: the fastest velocity change to it (jerk-limited, jerk_profile.hpp),
//   followed exactly (segment by segment) for the cycle's dt;
// - position goals: the time-optimal trajectory (trajectory.hpp) from the current state to
//   rest there, all position-goal joints arriving together, sampled at dt.
// A joint never leaves its position range: a velocity goal is capped so that the joint can
// still stop before the end of its range with half its acceleration and jerk (it slows down
// as it nears it), and a step that would leave it unable to stop there with the full limits
// brakes instead. Position goals are clamped into the range, and kept under their own speed
// cap when they carry one.
// Pure code: value types in and out, no I/O, no allocation once reset.
#pragma once

#include <limits>
#include <span>

#include "core/error.hpp"
#include "motion/jerk_profile.hpp"
#include "motion/trajectory.hpp"

namespace armctl::motion {

struct ServoJoint {
  double lower = 0, upper = 0;  // position range (rad or m)
  JerkLimits limits;
};

struct ServoGoal {
  enum class Kind { velocity, position };
  Kind kind = Kind::velocity;
  double value = 0;  // rad/s or m/s; rad or m
  // A position goal's speed cap below the joint's velocity limit (rad/s or m/s): the caller's
  // own limit, such as reduced mode's tool speed turned into joint speeds. A joint moving
  // faster slows to it first, keeping its direction.
  double max_speed = std::numeric_limits<double>::infinity();
};

// The largest speed from which a joint at rest in acceleration can stop within `distance`
// (>= 0) under `limits`: a velocity goal toward the end of the range is capped to it.
double stopping_speed(double distance, const JerkLimits& limits);
// Where a joint moving at (v, a) comes to rest when it brakes as hard as `limits` allow,
// relative to where it is (signed).
double stopping_displacement(double velocity, double acceleration, const JerkLimits& limits);

class ServoGenerator {
 public:
  // Every joint at rest at `positions`. Errors (invalid_argument, naming the joint): a count
  // outside 1..kMaxTrajectoryJoints, limits that are not finite and > 0, a range with
  // lower > upper, a position that is not finite. A position outside the range is allowed
  // (a joint may stand a little beyond it): that joint may only move back in.
  Status reset(std::span<const ServoJoint> joints, std::span<const double> positions);

  // Advances every joint `dt` s (> 0) toward its goal (one per joint). A goal that is not
  // finite counts as velocity 0. `together`: the velocity goals' changes are synchronized
  // (each joint's acceleration and jerk scaled to the slowest joint's profile), so that
  // joints whose velocities stand in a ratio keep it while they change: a tool moving on a
  // line starts and stops on it.
  void step(std::span<const ServoGoal> goals, double dt, bool together = false);

  // The joints' state, to go back to when a step turned out unwanted (the servo loop brakes
  // instead when the step's resting place would touch something).
  struct State {
    JointArray position{}, velocity{}, acceleration{};
  };
  State state() const { return {position_, velocity_, acceleration_}; }
  void restore(const State& s) {
    position_ = s.position;
    velocity_ = s.velocity;
    acceleration_ = s.acceleration;
  }
  // Where each joint comes to rest if it brakes as hard as its limits allow from now.
  JointArray resting_place() const;

  int joints() const { return count_; }
  const JointArray& position() const { return position_; }
  const JointArray& velocity() const { return velocity_; }
  const JointArray& acceleration() const { return acceleration_; }
  // Every joint still (velocity and acceleration below what rounding leaves).
  bool at_rest() const;
  // Per joint: whether its goal was capped this step by the end of its range.
  bool limited(int joint) const { return limited_[joint]; }
  // The velocity cap toward `direction` (+1 / -1) for `joint` where it stands now
  // (stopping_speed to the end of its range at half its limits, or its velocity limit).
  double velocity_cap(int joint, double direction) const;

 private:
  void step_velocity(int joint, double goal, double dt, const JerkLimits& limits);
  // Per velocity-goal joint, the limits that make its change as long as the slowest one's.
  void synchronize(std::span<const ServoGoal> goals, JerkLimits* limits) const;
  void step_positions(std::span<const ServoGoal> goals, double dt);

  int count_ = 0;
  ServoJoint joints_[kMaxTrajectoryJoints]{};
  JointArray position_{}, velocity_{}, acceleration_{};
  bool limited_[kMaxTrajectoryJoints]{};
  Trajectory trajectory_;  // reused: position goals plan into it every cycle
};

}  // namespace armctl::motion

#include "motion/servo_generator.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace armctl::motion {
namespace {

// Below these a joint counts as still (what rounding leaves of a profile's end).
constexpr double kRestVelocity = 1e-9, kRestAcceleration = 1e-9;

VelocityChange change_to(double v0, double a0, double v1, const JerkLimits& limits) {
  return velocity_change(v0, a0, v1, limits, 1 / limits.jerk, 1 / limits.acceleration);
}

// Follows the fastest velocity change from (p, v, a) to `goal` for `dt`, exactly: its three
// constant-jerk pieces, then a cruise at the goal velocity.
void follow_change(double& p, double& v, double& a, double goal, const JerkLimits& limits, double dt) {
  const VelocityChange c = change_to(v, a, goal, limits);
  const double durations[3] = {c.ramp_up, c.hold, c.ramp_down};
  const double jerks[3] = {c.jerk, 0, -c.jerk};
  JerkSegment s{0, 0, p, v, a, 0};
  for (int k = 0; k < 3 && dt > 0; ++k) {
    const double t = std::min(dt, durations[k]);
    s.jerk = jerks[k];
    const JerkState e = advance(s, t);
    s.position = e.position;
    s.velocity = e.velocity;
    s.acceleration = e.acceleration;
    dt -= t;
  }
  if (dt > 0) {  // the change is over: exactly at the goal velocity from here
    s.velocity = goal;
    s.acceleration = 0;
    s.position += goal * dt;
  }
  p = s.position;
  v = s.velocity;
  a = std::clamp(s.acceleration, -limits.acceleration, limits.acceleration);
}

JerkLimits half(const JerkLimits& l) { return {l.velocity, 0.5 * l.acceleration, 0.5 * l.jerk}; }

bool valid_limit(double x) { return std::isfinite(x) && x >= kMinTrajectoryLimit && x <= kMaxTrajectoryMagnitude; }

}  // namespace

double stopping_speed(double distance, const JerkLimits& limits) {
  if (!(distance > 0)) return 0;
  const double a = limits.acceleration, j = limits.jerk;
  // From (v, 0) to rest, symmetric: the displacement is v times half the change's time.
  // Triangular in acceleration (v <= a^2 / j): d = v^1.5 / sqrt(j).
  const double triangular = std::cbrt(distance * distance * j);
  double v = triangular;
  // With a plateau at a: d = v (v / a + a / j) / 2, a quadratic in v.
  if (triangular * j > a * a) v = 0.5 * (-a * a / j + std::sqrt(a * a * a * a / (j * j) + 8 * a * distance));
  return std::min(v, limits.velocity);
}

double stopping_displacement(double velocity, double acceleration, const JerkLimits& limits) {
  return change_to(velocity, acceleration, 0, limits).displacement;
}

Status ServoGenerator::reset(std::span<const ServoJoint> joints, std::span<const double> positions) {
  if (joints.empty() || joints.size() > std::size_t(kMaxTrajectoryJoints) || positions.size() != joints.size())
    return Error{ErrorKind::invalid_argument,
                 fmt::format("the servo generator drives 1..{} joints with one position each, not {} joints and {} "
                             "positions",
                             kMaxTrajectoryJoints, joints.size(), positions.size())};
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const ServoJoint& j = joints[i];
    if (!valid_limit(j.limits.velocity) || !valid_limit(j.limits.acceleration) || !valid_limit(j.limits.jerk))
      return Error{ErrorKind::invalid_argument,
                   fmt::format("joint {}: velocity, acceleration and jerk limits must be finite and in [{}, {}]", i + 1,
                               kMinTrajectoryLimit, kMaxTrajectoryMagnitude)};
    if (!std::isfinite(j.lower) || !std::isfinite(j.upper) || j.lower > j.upper)
      return Error{ErrorKind::invalid_argument,
                   fmt::format("joint {}: the position range {}..{} must be finite with lower <= upper", i + 1, j.lower,
                               j.upper)};
    if (!std::isfinite(positions[i]) || std::abs(positions[i]) > kMaxTrajectoryMagnitude)
      return Error{ErrorKind::invalid_argument,
                   fmt::format("joint {}: position {} is not a finite value within {}", i + 1, positions[i],
                               kMaxTrajectoryMagnitude)};
  }
  count_ = int(joints.size());
  for (int i = 0; i < count_; ++i) {
    joints_[i] = joints[i];
    position_[i] = positions[i];
    velocity_[i] = acceleration_[i] = 0;
    limited_[i] = false;
  }
  return Ok{};
}

bool ServoGenerator::at_rest() const {
  for (int i = 0; i < count_; ++i)
    if (std::abs(velocity_[i]) > kRestVelocity || std::abs(acceleration_[i]) > kRestAcceleration) return false;
  return true;
}

JointArray ServoGenerator::resting_place() const {
  JointArray rest = position_;
  for (int i = 0; i < count_; ++i)
    rest[i] += stopping_displacement(velocity_[i], acceleration_[i], joints_[i].limits);
  return rest;
}

double ServoGenerator::velocity_cap(int joint, double direction) const {
  const ServoJoint& j = joints_[joint];
  const double distance = direction > 0 ? j.upper - position_[joint] : position_[joint] - j.lower;
  return stopping_speed(distance, half(j.limits));
}

namespace {

bool is_position_goal(std::span<const ServoGoal> goals, int i) {
  return i < int(goals.size()) && goals[i].kind == ServoGoal::Kind::position && std::isfinite(goals[i].value);
}

double asked_velocity(std::span<const ServoGoal> goals, int i) {
  return i < int(goals.size()) && std::isfinite(goals[i].value) ? goals[i].value : 0.0;
}

}  // namespace

void ServoGenerator::step(std::span<const ServoGoal> goals, double dt, bool together) {
  if (!(dt > 0) || !std::isfinite(dt)) return;
  JerkLimits limits[kMaxTrajectoryJoints];
  for (int i = 0; i < count_; ++i) limits[i] = joints_[i].limits;
  if (together) synchronize(goals, limits);
  bool any_position = false;
  for (int i = 0; i < count_; ++i) {
    if (is_position_goal(goals, i)) {
      any_position = true;
      continue;
    }
    step_velocity(i, asked_velocity(goals, i), dt, limits[i]);
  }
  if (any_position) step_positions(goals, dt);
}

void ServoGenerator::synchronize(std::span<const ServoGoal> goals, JerkLimits* limits) const {
  // The slowest change sets the pace: a joint whose change is r times as large gets r times
  // its acceleration and jerk, so that its profile is the slowest one's scaled by r.
  int slowest = -1;
  double longest = 0;
  double change[kMaxTrajectoryJoints]{};
  for (int i = 0; i < count_; ++i) {
    if (is_position_goal(goals, i)) continue;
    const double asked = asked_velocity(goals, i);
    const double cap = velocity_cap(i, asked >= 0 ? 1 : -1);
    const double goal = std::clamp(asked, -cap, cap);
    change[i] = goal - velocity_[i];
    const double t = change_to(velocity_[i], acceleration_[i], goal, joints_[i].limits).duration;
    if (t > longest) {
      longest = t;
      slowest = i;
    }
  }
  if (slowest < 0 || change[slowest] == 0) return;
  const JerkLimits& pace = joints_[slowest].limits;
  for (int i = 0; i < count_; ++i) {
    if (i == slowest || is_position_goal(goals, i)) continue;
    const double r = std::abs(change[i] / change[slowest]);
    const JerkLimits& own = joints_[i].limits;
    // Never beyond the joint's own limits, never below what its acceleration now needs.
    const double a_now = std::abs(acceleration_[i]);
    limits[i].acceleration = std::clamp(pace.acceleration * r, std::max(a_now, kMinTrajectoryLimit),
                                        std::max(own.acceleration, a_now));
    limits[i].jerk = std::clamp(pace.jerk * r, kMinTrajectoryLimit, own.jerk);
  }
}

void ServoGenerator::step_velocity(int i, double goal, double dt, const JerkLimits& limits) {
  const ServoJoint& j = joints_[i];
  const double cap = velocity_cap(i, goal >= 0 ? 1 : -1);
  limited_[i] = std::abs(goal) > cap;
  goal = std::clamp(goal, -cap, cap);
  // Never further out than the range, or than where the joint stands if it is outside.
  const double lo = std::min(j.lower, position_[i]), hi = std::max(j.upper, position_[i]);
  double p = position_[i], v = velocity_[i], a = acceleration_[i];
  follow_change(p, v, a, goal, limits, dt);
  const double rest = p + stopping_displacement(v, a, j.limits);
  if (rest > hi || rest < lo) {
    // This step would leave the joint unable to stop inside: brake now instead (from a state
    // that could stop inside, braking keeps it so).
    p = position_[i];
    v = velocity_[i];
    a = acceleration_[i];
    follow_change(p, v, a, 0, j.limits, dt);
    limited_[i] = true;
  }
  position_[i] = p;
  velocity_[i] = v;
  acceleration_[i] = a;
}

void ServoGenerator::step_positions(std::span<const ServoGoal> goals, double dt) {
  TrajectoryInput in;
  int index[kMaxTrajectoryJoints];
  int m = 0;
  bool capped = false, faster = false;
  for (int i = 0; i < count_; ++i) {
    if (!(i < int(goals.size()) && goals[i].kind == ServoGoal::Kind::position && std::isfinite(goals[i].value)))
      continue;
    const ServoJoint& j = joints_[i];
    index[m] = i;
    // Rounding may leave the state a hair beyond a limit the generator refuses.
    in.velocity[m] = std::clamp(velocity_[i], -j.limits.velocity, j.limits.velocity);
    in.acceleration[m] = std::clamp(acceleration_[i], -j.limits.acceleration, j.limits.acceleration);
    in.position[m] = position_[i];
    in.target_position[m] = std::clamp(goals[i].value, j.lower, j.upper);
    limited_[i] = in.target_position[m] != goals[i].value;
    const double cap = std::clamp(goals[i].max_speed, kMinTrajectoryLimit, j.limits.velocity);
    capped = capped || cap < j.limits.velocity;
    // (Slowing to a cap may leave the velocity a rounding error above it.)
    faster = faster || std::abs(velocity_[i]) > cap * (1 + 1e-9);
    in.velocity[m] = std::clamp(in.velocity[m], -cap, cap);
    in.max_velocity[m] = cap;
    in.max_acceleration[m] = j.limits.acceleration;
    in.max_jerk[m] = j.limits.jerk;
    ++m;
  }
  in.joints = m;
  if (faster || !calculate_trajectory(in, trajectory_)) {
    // A start the generator cannot plan from (the velocity limit cannot be kept): brake, or
    // under a cap (that may have just come down) slow to it, each joint keeping its direction.
    for (int k = 0; k < m; ++k) {
      const int i = index[k];
      const double goal = capped ? std::clamp(velocity_[i], -in.max_velocity[k], in.max_velocity[k]) : 0.0;
      step_velocity(i, goal, dt, joints_[i].limits);
    }
    return;
  }
  const TrajectoryState s = trajectory_.at(dt);
  for (int k = 0; k < m; ++k) {
    position_[index[k]] = s.position[k];
    velocity_[index[k]] = s.velocity[k];
    acceleration_[index[k]] = s.acceleration[k];
  }
}

}  // namespace armctl::motion

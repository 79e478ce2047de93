#include "arm/run_servo.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "arm/servo_twist.hpp"
#include "core/quantity.hpp"
#include "motion/servo_generator.hpp"
#include "scene/collision_world.hpp"
#include "scene/motion_check.hpp"

namespace armctl::arm {

const char* to_string(ServoSlowdown why) {
  switch (why) {
    case ServoSlowdown::none: return "none";
    case ServoSlowdown::joint_limit: return "joint limit";
    case ServoSlowdown::singularity: return "singularity";
    case ServoSlowdown::collision: return "collision";
    case ServoSlowdown::unreachable: return "unreachable";
    case ServoSlowdown::command_timeout: return "command timeout";
  }
  return "?";
}

namespace {

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

// How far ahead a command's direction is looked at to tell whether it moves toward a
// singularity or an obstacle, and how near they are there (s of motion at the commanded
// velocity: about the time the joints take to stop).
constexpr double kLookAhead = 0.2;
// Nearer than this within the look-ahead counts as moving toward something (m).
constexpr double kCloser = 1e-4;
// Position targets aim this far under reduced mode's tool speed cap: the caps are taken where
// the arm stands at the start of each cycle, and the arm moves on during it.
constexpr double kToolSpeedMargin = 0.95;

Status check_options(const ServoOptions& o) {
  if (auto ok = check_fraction_in(o.speed, "servo speed", motion::kMinSpeedFraction, motion::kMaxSpeedFraction); !ok)
    return ok;
  if (o.command_timeout <= Duration{0})
    return Error{ErrorKind::invalid_argument, "servo command timeout: a time above 0 is needed"};
  if (o.period && *o.period <= Duration{0})
    return Error{ErrorKind::invalid_argument, "servo period: a time above 0 is needed"};
  if (!(o.max_linear_speed > 0) || !(o.max_angular_speed > 0) || !std::isfinite(o.max_linear_speed) ||
      !std::isfinite(o.max_angular_speed))
    return Error{ErrorKind::invalid_argument, "servo speed caps: finite linear (m/s) and angular (rad/s) speeds above 0"};
  if (!(o.singularity_slow >= 1 && o.singularity_stop > o.singularity_slow))
    return Error{ErrorKind::invalid_argument, "servo singularity thresholds: 1 <= slow < stop"};
  if (!(o.collision_stop >= 0 && o.collision_slow > o.collision_stop && o.collision_slow <= scene::kClearanceHorizon))
    return Error{ErrorKind::invalid_argument,
                 fmt::format("servo collision distances: 0 <= stop < slow <= {} m", scene::kClearanceHorizon)};
  return Ok{};
}

Eigen::Vector3d clipped(const Eigen::Vector3d& v, double most) {
  const double n = v.norm();
  return n > most ? Eigen::Vector3d(v * (most / n)) : v;
}

class ServoLoop {
 public:
  ServoLoop(Arm& arm, ServoInput& input, const ServoOptions& options)
      : arm_(arm), input_(input), options_(options), kinematics_(arm.kinematics()), model_(kinematics_->model()),
        device_(arm.device()), clock_(arm.clock()), stall_(arm.stall_watch(options.executor.stall_time)),
        n_(std::size_t(model_.joint_count())), goals_(n_),
        positions_(n_), velocities_(n_), sent_(n_) {}

  Result<ServoReport> run() {
    if (auto ok = check_options(options_); !ok) return ok.error();
    if (n_ > std::size_t(motion::kMaxTrajectoryJoints))
      return Error{ErrorKind::invalid_config,
                   fmt::format("arm '{}' has {} joints; the servo mode drives at most {}", model_.name, n_,
                               motion::kMaxTrajectoryJoints)};
    auto start_state = arm_.read();
    if (!start_state) return start_state.error();
    std::vector<motion::ServoJoint> joints(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      const JointLimits& l = model_.joints[i].limits;
      joints[i] = {l.lower, l.upper, motion::JerkLimits{l.velocity * options_.speed, l.acceleration, l.jerk}};
    }
    // Reduced mode's narrower ranges slow the joints toward their ends as the joint limits do
    // (a joint that starts outside its range keeps its own limits: it may move back in).
    if (const auto& reduced = kinematics_->reduced())
      for (const scene::JointRange& r : reduced->joint_ranges) {
        const double q = start_state->positions[r.joint];
        if (q >= r.lower && q <= r.upper) {
          joints[r.joint].lower = r.lower;
          joints[r.joint].upper = r.upper;
        }
      }
    if (auto ok = generator_.reset(joints, start_state->positions); !ok) return ok.error();
    sent_ = start_state->positions;
    world_ = kinematics_->collisions();
    // Pairs already touching at the start may move apart: they are not held against it.
    if (world_) {
      skip_ = world_->touching(start_state->positions);
      beyond_ = scene::LimitsBeyond(*world_, skip_);
    }
    if (model_.gripper) gripper_ = start_state->positions[std::size_t(model_.gripper->joint)];

    report_.period = options_.period.value_or(device_.stream_period(false));
    if (report_.period <= Duration{0}) report_.period = std::chrono::milliseconds(1);
    // How the arm is read back (docs/servo.md "One cycle"): on a full-duplex line in two
    // halves, the request after one cycle's point and the reply taken after the next one's;
    // where every joint is read alone (the joint bus), one joint after each point until all
    // are read; otherwise whole, after a point. The first two hold the line for a request or
    // one joint only, so a point never waits long behind a read-back. `read_time`: how much
    // longer a cycle with a read lasts.
    Duration read_time = device_.stream_period(true) - device_.stream_period(false);
    if (const auto request = device_.read_request_time()) {
      read_way_ = ReadWay::halves;
      read_time = *request;
    } else if (const auto joint = device_.joint_read_time()) {
      read_way_ = ReadWay::joint_by_joint;
      read_time = *joint;
      swept_device_.assign(n_, 0.0);
      swept_sent_.assign(n_, 0.0);
    }
    const Duration read_every =
        options_.executor.read_interval.value_or(std::max(device_.poll_interval(), 4 * report_.period));
    const TimePoint start = clock_.now();
    TimePoint next_read = start + read_every;

    for (;;) {
      const TimePoint now = clock_.now();
      if (options_.before_cycle) options_.before_cycle(now);
      const ServoInput::Newest newest = input_.take(seen_);
      if (newest.sequence != seen_ && newest.command) receive(*newest.command, now);
      seen_ = newest.sequence;
      const bool commanded = command_ && !newest.finish && now - received_ <= options_.command_timeout;

      ServoStatus status;
      goals_for(commanded, status);
      if (command_ && !commanded && !newest.finish) status.slowdown = ServoSlowdown::command_timeout;
      // The point goes out now and is reached `in` from now (a cycle with a read-back lasts
      // longer): the generator steps by as much.
      const bool read_now = now >= next_read || swept_ > 0;
      const Duration in = report_.period + (read_now ? read_time : Duration{0});
      step(seconds(in), status);

      for (std::size_t i = 0; i < n_; ++i) {
        positions_[i] = generator_.position()[i];
        velocities_[i] = generator_.velocity()[i];
      }
      std::vector<double> dq, dv;
      to_device(model_, device_.protocol(), positions_, velocities_, dq, dv);
      if (auto s = device_.stream(dq, dv, in); !s) return halted(s.error());
      ++report_.cycles;
      if (status.slowdown != ServoSlowdown::none) ++report_.slowed[std::size_t(status.slowdown)];
      // (A stall has stopped the arm and released the joint: a halt would hold it again.)
      if (auto f = read_after_point(read_now); !f) return stall_of(f.error()) ? f.error() : halted(f.error());
      if (read_now && swept_ == 0) next_read = clock_.now() + read_every;  // a read made or requested
      sent_ = positions_;
      status.elapsed = now + in - start;  // when the point is due (a read-back's wait is not in it)
      status.positions = positions_;
      status.velocities = velocities_;
      status.commanded = commanded;
      status.at_rest = generator_.at_rest();
      status.commands = report_.commands;
      if (options_.on_cycle) options_.on_cycle(status);
      if (newest.finish && status.at_rest) break;
      const TimePoint due_next = now + in;
      if (due_next > clock_.now())
        if (auto s = device_.idle(due_next - clock_.now()); !s) return halted(s.error());
    }
    if (requested_)  // the last request's reply, so that no late reply is left on the line
      if (auto f = read_back(requested_sent_); !f) return stall_of(f.error()) ? f.error() : halted(f.error());
    arm_.expect_at(positions_);
    report_.positions = positions_;
    report_.elapsed = clock_.now() - start;
    return report_;
  }

 private:
  void receive(const ServoCommand& command, TimePoint now) {
    command_ = command;
    received_ = now;
    ++report_.commands;
    if (command.gripper && model_.gripper) gripper_ = model_.gripper->at(*command.gripper);
    targets_.clear();
    unreachable_.clear();
    if (const auto* p = std::get_if<PoseTarget>(&command_->motion)) {
      // Solved when the goal changes, near where the arm is now: every cycle then steers to
      // it (a goal renewed as it is keeps its solution instead of wandering among others).
      if (!same_goal(pose_goal_, p->goal)) solve(p->goal);
      targets_ = pose_targets_;
      if (targets_.empty()) unreachable_ = pose_error_;
    } else if (const auto* t = std::get_if<JointTargets>(&command_->motion)) {
      targets_.resize(n_);
      for (std::size_t i = 0; i < n_; ++i) targets_[i] = t->values[i].value_or(NAN);
    }
  }

  static bool same_goal(const std::optional<CartesianGoal>& a, const CartesianGoal& b) {
    return a && a->position == b.position && a->roll == b.roll && a->pitch == b.pitch && a->yaw == b.yaw &&
           a->elbow == b.elbow && a->nearest_orientation == b.nearest_orientation;
  }

  // A goal without an orientation keeps the tool's (a hand moving a leader, a point picked
  // on a screen mean "there, as it is"), or takes any that reaches when that one does not.
  void solve(const CartesianGoal& goal) {
    pose_goal_ = goal;
    pose_targets_.clear();
    CartesianGoal kept = goal;
    if (!goal.roll && !goal.pitch && !goal.yaw) {
      const motion::Rpy now = kinematics_->tool_rpy_at(sent_);
      kept = kinematics_->keeping_orientation(goal.position, now);
      kept.elbow = goal.elbow;
    }
    auto solved = kinematics_->nearest_joints(kept, sent_);
    if (!solved) solved = kinematics_->nearest_joints(goal, sent_);
    if (solved) pose_targets_.assign(solved->begin(), solved->end());
    else pose_error_ = solved.error().message;
  }

  // One goal per joint for this cycle, and why it is slower than asked.
  void goals_for(bool commanded, ServoStatus& status) {
    using Kind = motion::ServoGoal::Kind;
    for (auto& g : goals_) g = {Kind::velocity, 0};
    capped_positions_ = false;
    // A twist's joints change their velocities together (the tool stays on its line); so do
    // they when they stop (the command ended, timed out): the ratio they had is kept.
    together_ = !commanded || std::holds_alternative<ToolTwist>(command_->motion);
    if (commanded) {
      if (const auto* t = std::get_if<ToolTwist>(&command_->motion)) {
        twist_goals(*t, status);
      } else if (const auto* v = std::get_if<JointVelocities>(&command_->motion)) {
        for (std::size_t i = 0; i < n_; ++i) goals_[i] = {Kind::velocity, v->values[i]};
        cap_tool_speed(status);
        scale_near_obstacles(status);
      } else if (!unreachable_.empty()) {
        status.slowdown = ServoSlowdown::unreachable;
        status.detail = unreachable_;
      } else {
        for (std::size_t i = 0; i < n_ && i < targets_.size(); ++i)
          if (std::isfinite(targets_[i])) goals_[i] = {Kind::position, targets_[i]};
        cap_position_speeds(status);
      }
    }
    // The gripper goes to its last target whether commands come or not: it is a place,
    // not a motion that must be renewed.
    if (model_.gripper && std::isfinite(gripper_)) goals_[std::size_t(model_.gripper->joint)] = {Kind::position, gripper_};
  }

  void twist_goals(const ToolTwist& twist, ServoStatus& status) {
    const motion::JointVector chain = kinematics_->chain_of(sent_);
    Eigen::Vector3d linear = clipped(twist.linear, std::min(options_.max_linear_speed, tool_speed_cap()));
    Eigen::Vector3d angular = clipped(twist.angular, options_.max_angular_speed);
    if (twist.frame == ServoFrame::tool) {
      const Eigen::Matrix3d r = kinematics_->forward(chain).orientation.toRotationMatrix();
      linear = r * linear;
      angular = r * angular;
    }
    const motion::Jacobian jacobian = tool_jacobian(*kinematics_, chain);
    const motion::JointVector q = joint_velocities_for(jacobian, linear, angular);
    double scale = 1;
    // Every joint within its velocity limit and what lets it stop before the end of its
    // range: the whole twist is scaled, so the tool keeps its direction.
    for (int i = 0; i < q.size(); ++i) {
      if (q[i] == 0) continue;
      const double vmax = model_.joints[std::size_t(i)].limits.velocity * options_.speed;
      const double cap = generator_.velocity_cap(i, q[i] > 0 ? 1 : -1);
      const double s = std::min(vmax, cap) / std::abs(q[i]);
      if (s < scale) {
        scale = s;
        status.slowdown = ServoSlowdown::joint_limit;
        status.detail = model_.joints[std::size_t(i)].name +
                        (cap < vmax ? " near the end of its range" : " at its velocity limit");
      }
    }
    // Toward a singularity (only then: moving away is how one leaves it), slowed by how near
    // it is where the command leads within the look-ahead.
    const double here = position_condition(jacobian);
    const motion::JointVector ahead = chain + q * (scale * kLookAhead);
    const double there = position_condition(tool_jacobian(*kinematics_, ahead));
    if (there > here && there > options_.singularity_slow) {
      const double s = std::clamp(
          (options_.singularity_stop - there) / (options_.singularity_stop - options_.singularity_slow), 0.0, 1.0);
      if (s < scale) {
        scale = s;
        status.slowdown = ServoSlowdown::singularity;
        status.detail = fmt::format("condition {:.1f}", there);
      }
    }
    // At a singularity a direction may be lost altogether (the SCARA stretched out cannot
    // move its tool outward): the damped solve gives the joints next to nothing, and the
    // status says why the tool does not move as asked.
    const double asked = linear.norm(), made = (jacobian.topRows<3>() * q).norm();
    if (status.slowdown == ServoSlowdown::none && asked > 0 && made < 0.5 * asked) {
      status.slowdown = ServoSlowdown::singularity;
      status.detail = fmt::format("condition {:.1f}: the tool cannot move that way here", here);
    }
    for (int i = 0; i < q.size(); ++i) goals_[std::size_t(i)] = {motion::ServoGoal::Kind::velocity, q[i] * scale};
    status.scale = scale;
    scale_near_obstacles(status);
  }

  // Reduced mode's cap on the tool speed (infinite without one).
  double tool_speed_cap() const {
    const auto& reduced = kinematics_->reduced();
    return reduced && reduced->tool_speed ? *reduced->tool_speed : std::numeric_limits<double>::infinity();
  }

  // The tool point's speed (m/s) where the arm was sent last, chain joint i moving at
  // velocity(i) (rad/s or m/s): a twist, the goals, the generator's state.
  template <typename Velocity>
  double tool_point_speed(Velocity velocity) const {
    const motion::JointVector chain = kinematics_->chain_of(sent_);
    motion::JointVector qd(chain.size());
    for (int i = 0; i < qd.size(); ++i) qd[i] = velocity(std::size_t(i));
    return (tool_jacobian(*kinematics_, chain).topRows<3>() * qd).norm();
  }

  void report_reduced_speed(ServoStatus& status) const {
    status.slowdown = ServoSlowdown::joint_limit;
    status.detail = fmt::format("the tool at reduced mode's {:.1f} mm/s", tool_speed_cap() * 1e3);
  }

  // Joint velocities that would move the tool faster than reduced mode's cap, scaled down together.
  void cap_tool_speed(ServoStatus& status) {
    const double cap = tool_speed_cap();
    if (!std::isfinite(cap)) return;
    const double speed = tool_point_speed([&](std::size_t i) { return goals_[i].value; });
    if (speed <= cap) return;
    const double s = cap / speed;
    for (std::size_t i = 0; i < std::size_t(model_.chain_joints()); ++i) goals_[i].value *= s;
    if (s < status.scale) {
      status.scale = s;
      report_reduced_speed(status);
    }
  }

  // Position goals (joint and pose targets) under reduced mode's tool speed cap. The joints
  // of a synchronized move go at speeds in proportion to what each has left to go (d), so the
  // tool point moves at (speed) |J d| / |d|: each chain joint's speed is capped in
  // proportion to its |d_i|, so that the tool point's speed stays under the cap. Recomputed
  // every cycle from where the arm is and what is left; step() checks the result and steps
  // again slower when the tool would still go faster (the joints not yet in proportion).
  void cap_position_speeds(ServoStatus& status) {
    const double cap = kToolSpeedMargin * tool_speed_cap();
    if (!std::isfinite(cap)) return;
    const auto left = [&](std::size_t i) {
      const motion::ServoGoal& g = goals_[i];
      return g.kind == motion::ServoGoal::Kind::position ? g.value - sent_[i] : 0.0;
    };
    const double tool = tool_point_speed(left);  // of a unit of time's worth of what is left
    if (!(tool > 0)) return;  // nothing left that moves the tool point
    bool at_cap = false;
    for (std::size_t i = 0; i < std::size_t(model_.chain_joints()); ++i) {
      motion::ServoGoal& g = goals_[i];
      if (g.kind != motion::ServoGoal::Kind::position) continue;
      g.max_speed = cap * std::abs(left(i)) / tool;
      // (Reported while a joint is held at its cap: near its target it slows of itself.)
      at_cap = at_cap || (g.max_speed < model_.joints[i].limits.velocity * options_.speed &&
                          std::abs(generator_.velocity()[i]) >= 0.95 * g.max_speed);
    }
    capped_positions_ = true;
    if (at_cap) report_reduced_speed(status);
  }

  // Velocity goals toward something nearer than collision_slow are scaled down with the
  // clearance (only toward it: moving away is not held back).
  void scale_near_obstacles(ServoStatus& status) {
    if (!world_) return;
    const scene::Clearance now = world_->clearance(sent_, options_.collision_slow, skip_);
    if (now.distance >= options_.collision_slow) return;
    std::vector<double> ahead = sent_;
    for (std::size_t i = 0; i < n_; ++i)
      if (goals_[i].kind == motion::ServoGoal::Kind::velocity) ahead[i] += goals_[i].value * kLookAhead;
    // Toward it means nearer by more than rounding (links that keep their distance, such as
    // a joint's two sides, are not slowed for).
    if (world_->clearance(ahead, options_.collision_slow, skip_).distance >= now.distance - kCloser) return;
    const double s = std::clamp((now.distance - options_.collision_stop) /
                                    (options_.collision_slow - options_.collision_stop),
                                0.0, 1.0);
    for (std::size_t i = 0; i < n_; ++i)
      if (goals_[i].kind == motion::ServoGoal::Kind::velocity) goals_[i].value *= s;
    if (s < status.scale) {
      status.scale *= s;
      status.slowdown = ServoSlowdown::collision;
      status.detail = fmt::format("{} and {} {:.1f} mm apart", now.first, now.second, now.distance * 1000);
    }
  }

  // One step; if where the arm would come to rest from there touches anything, a braking
  // step instead (from a resting place that was clear, braking keeps it clear).
  void step(double dt, ServoStatus& status) {
    const motion::ServoGenerator::State before = generator_.state();
    generator_.step(goals_, dt, together_);
    // Position goals under reduced mode's cap whose joints are not yet in proportion: once
    // more, each joint's cap lowered by as much as the tool would go too fast.
    if (capped_positions_) {
      const double cap = kToolSpeedMargin * tool_speed_cap();
      const double speed = tool_point_speed([&](std::size_t i) { return generator_.velocity()[i]; });
      if (speed > cap) {
        generator_.restore(before);
        for (auto& g : goals_)
          if (g.kind == motion::ServoGoal::Kind::position) g.max_speed *= cap / speed;
        generator_.step(goals_, dt, together_);
      }
    }
    for (std::size_t i = 0; i < n_; ++i)
      if (generator_.limited(int(i)) && status.slowdown == ServoSlowdown::none) {
        status.slowdown = ServoSlowdown::joint_limit;
        status.detail = model_.joints[i].name;
      }
    if (!world_) return;
    const motion::JointArray rest = generator_.resting_place();
    const std::span<const double> resting(rest.data(), n_);
    // A limit broken at the start (the fence switched on with the tool outside): the arm may
    // come back, never go further beyond it than it has been.
    std::optional<scene::Contact> deeper;
    if (!beyond_.empty()) {
      world_->place(resting, placed_);
      deeper = beyond_.deeper(resting, placed_, false);
    }
    if (!deeper && !world_->collides(resting, skip_)) return note_beyond();
    generator_.restore(before);
    std::vector<motion::ServoGoal> brake(n_);
    // The gripper keeps going where it was sent: it is not part of what is checked moving.
    if (model_.gripper) brake[std::size_t(model_.gripper->joint)] = goals_[std::size_t(model_.gripper->joint)];
    generator_.step(brake, dt);
    status.scale = 0;
    status.slowdown = ServoSlowdown::collision;
    if (deeper)
      status.detail = fmt::format("{} would leave {}", deeper->first, deeper->second);
    else if (auto c = world_->contact(resting, skip_))
      status.detail =
          fmt::format("{} would {} {}", c->first, c->limit == scene::Limit::none ? "touch" : "leave", c->second);
    note_beyond();
  }

  // The limits broken at the start take the depth where the arm is now as their least.
  void note_beyond() {
    if (beyond_.empty()) return;
    const std::span<const double> now(generator_.position().data(), n_);
    world_->place(now, placed_);
    (void)beyond_.deeper(now, placed_, true);
  }

  // The cycle's part of a read-back, after its point (`read_now`: one is due or under way).
  Status read_after_point(bool read_now) {
    switch (read_way_) {
      case ReadWay::whole:
        return read_now ? read_back(sent_) : Status{Ok{}};
      case ReadWay::halves:
        if (requested_) {
          requested_ = false;
          if (auto f = read_back(requested_sent_); !f) return f;
        }
        if (!read_now) return Ok{};
        if (auto r = device_.request_read(); !r) return r;
        requested_ = true;
        requested_sent_ = sent_;
        return Ok{};
      case ReadWay::joint_by_joint: {
        if (!read_now) return Ok{};
        const std::size_t j = swept_;
        auto q = device_.read_joint(int(j));
        if (!q) return q.error();
        swept_device_[j] = *q;
        swept_sent_[j] = sent_[j];
        if (++swept_ < n_) return Ok{};
        swept_ = 0;
        JointState s;
        s.time = clock_.now();
        s.device = swept_device_;
        s.positions = model_.from_device(device_.protocol(), s.device);
        return check_read(s, swept_sent_);
      }
    }
    return Ok{};
  }

  // `sent`: the point before the one sent last when the read was made (or requested).
  Status read_back(const std::vector<double>& sent) {
    auto s = arm_.read();
    if (!s) return s.error();
    return check_read(*s, sent);
  }

  // A reading of every joint; `sent` per joint, the point before the one sent last when it
  // was read.
  Status check_read(const JointState& s, const std::vector<double>& sent) {
    ++report_.reads;
    if (options_.executor.on_read) options_.executor.on_read(s);
    // The device is on its way to the point sent last; it was sent the one before it.
    if (auto f = check_following(model_, s.positions, sent, options_.executor, "servo", 0,
                                 report_.largest_following_error, report_.largest_following_joint);
        !f)
      return f;
    // Stall protection (arm/stall_watch.hpp): a joint driven but standing still (something the
    // scene does not know in the way) stops the arm and has its torque released.
    driven_.assign(sent.begin(), sent.end());
    if (auto stall = stall_.read(s.time, s.positions, driven_)) return arm_.stalled(std::move(*stall), "servo");
    return Ok{};
  }

  Error halted(const Error& e) {
    (void)device_.stop();  // best effort: the error is what the caller needs
    return e;
  }

  Arm& arm_;
  ServoInput& input_;
  const ServoOptions& options_;
  std::shared_ptr<const ArmKinematics> kinematics_;
  const ArmModel& model_;
  ArmDevice& device_;
  const Clock& clock_;
  StallWatch stall_;
  std::vector<std::optional<double>> driven_;  // where the joints were sent, for the stall watch
  const std::size_t n_;
  motion::ServoGenerator generator_;
  std::vector<motion::ServoGoal> goals_;
  std::vector<double> positions_, velocities_, sent_;
  enum class ReadWay { whole, halves, joint_by_joint };
  ReadWay read_way_ = ReadWay::whole;
  bool requested_ = false;              // halves: a read's request is out, its reply not yet taken
  std::vector<double> requested_sent_;  // sent_ when it went out
  std::size_t swept_ = 0;               // joint by joint: the joints read so far in this read
  std::vector<double> swept_device_, swept_sent_;  // each one's reading, and sent_ then
  std::shared_ptr<const scene::CollisionWorld> world_;
  std::vector<int> skip_;
  scene::LimitsBeyond beyond_;
  scene::CollisionWorld::Placement placed_;
  std::optional<ServoCommand> command_;
  TimePoint received_{};
  std::uint64_t seen_ = 0;
  std::vector<double> targets_;  // of a joint or pose target (NaN: keep still)
  std::string unreachable_;      // why a pose target has no solution
  std::optional<CartesianGoal> pose_goal_;  // the last pose target solved, its joints, or why not
  std::vector<double> pose_targets_;
  std::string pose_error_;
  double gripper_ = NAN;         // its target
  bool together_ = false;        // velocity changes synchronized this cycle
  bool capped_positions_ = false;  // position goals capped by reduced mode's tool speed this cycle
  ServoReport report_;
};

}  // namespace

Result<ServoReport> run_servo(Arm& arm, ServoInput& input, const ServoOptions& options) {
  return ServoLoop(arm, input, options).run();
}

}  // namespace armctl::arm

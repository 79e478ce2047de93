#include "ros/arm_node.hpp"

#include <chrono>
#include <cmath>
#include <atomic>
#include <condition_variable>
#include <list>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/JointJog.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/BatteryState.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <trajectory_msgs/JointTrajectory.h>

#include "armctl_msgs/MoveTo.h"
#include "armctl_msgs/RunActionGroup.h"
#include "armctl_msgs/RemoveSceneObject.h"
#include "armctl_msgs/SetGripper.h"
#include "armctl_msgs/SetSceneObject.h"

namespace armctl::ros_node {

void NodeCounters::refusal(const std::string& why) {
  std::lock_guard<std::mutex> lock(mutex);
  ++refused;
  last_refusal = why;
}

void NodeCounters::failure(const std::string& why) {
  std::lock_guard<std::mutex> lock(mutex);
  ++failed;
  last_failure = why;
}

namespace {

using Action = control_msgs::FollowJointTrajectoryAction;
using Server = actionlib::ActionServer<Action>;
using GoalHandle = Server::GoalHandle;
using control_msgs::FollowJointTrajectoryResult;

TrajectoryRequest request_of(const trajectory_msgs::JointTrajectory& t) {
  TrajectoryRequest r;
  r.joint_names = t.joint_names;
  for (const auto& p : t.points) {
    TrajectoryPoint q;
    q.time = p.time_from_start.toSec();
    q.positions = p.positions;
    q.velocities = p.velocities;
    q.accelerations = p.accelerations;
    q.effort = p.effort;
    r.points.push_back(std::move(q));
  }
  return r;
}

std::vector<JointTolerance> tolerances_of(const std::vector<control_msgs::JointTolerance>& given) {
  std::vector<JointTolerance> out;
  for (const auto& t : given) out.push_back({t.name, t.position});
  return out;
}

}  // namespace

struct ArmNode::Impl {
  ArmBridge& arm;
  NodeCounters& counters;
  const ArmInfo& info;
  std::string device;

  ros::NodeHandle nh, private_nh{"~"};
  ros::Publisher joint_states, battery, diagnostics;
  ros::Subscriber command, pose_goal, twist, joint_jog;
  std::vector<ros::ServiceServer> services;
  std::unique_ptr<Server> server;

  std::mutex mutex;
  bool quit = false;
  std::string active_goal;  // the newest accepted goal, waiting for its stamp or moving ("" = none)
  std::string moving_goal;  // the goal whose motion runs (an older one until a newer one starts)
  std::string canceled_goal;  // a cancel for the active goal before its motion started
  std::condition_variable goal_changed;  // active_goal, canceled_goal or quit
  struct Runner {
    std::thread thread;
    std::shared_ptr<std::atomic<bool>> done;
  };
  std::list<Runner> runners;  // one per accepted goal, streamed trajectory or pose goal
  std::thread publisher;

  Impl(ArmBridge& a, NodeCounters& c, const std::string& d) : arm(a), counters(c), info(a.info()), device(d) {
    nh.setParam("robot_description", info.urdf);
    joint_states = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
    battery = nh.advertise<sensor_msgs::BatteryState>("battery", 1);
    diagnostics = nh.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 1);
    command = nh.subscribe("arm_controller/command", 1, &Impl::on_command, this);
    pose_goal = nh.subscribe("pose_goal", 1, &Impl::on_pose_goal, this);
    // The servo mode, on MoveIt Servo's topic names and types (docs/ros.md "Servo").
    twist = private_nh.subscribe("delta_twist_cmds", 10, &Impl::on_twist, this);
    joint_jog = private_nh.subscribe("delta_joint_cmds", 10, &Impl::on_joint_jog, this);
    services.push_back(private_nh.advertiseService("stop", &Impl::on_stop, this));
    services.push_back(private_nh.advertiseService("set_torque", &Impl::on_torque, this));
    services.push_back(private_nh.advertiseService("clear_faults", &Impl::on_clear_faults, this));
    services.push_back(private_nh.advertiseService("gripper", &Impl::on_gripper, this));
    services.push_back(private_nh.advertiseService("move_to", &Impl::on_move_to, this));
    services.push_back(private_nh.advertiseService("run_action_group", &Impl::on_run_group, this));
    services.push_back(private_nh.advertiseService("stop_action_group", &Impl::on_stop_group, this));
    services.push_back(private_nh.advertiseService("scene/set_object", &Impl::on_set_scene_object, this));
    services.push_back(private_nh.advertiseService("scene/remove_object", &Impl::on_remove_scene_object, this));
    services.push_back(private_nh.advertiseService("set_fence", &Impl::on_set_fence, this));
    services.push_back(private_nh.advertiseService("set_reduced_mode", &Impl::on_set_reduced_mode, this));
    server = std::make_unique<Server>(nh, "arm_controller/follow_joint_trajectory",
                                      [this](GoalHandle g) { on_goal(g); }, [this](GoalHandle g) { on_cancel(g); },
                                      false);
    server->start();
    publisher = std::thread([this] { publish_loop(); });
  }

  ~Impl() {
    {
      std::lock_guard<std::mutex> lock(mutex);
      quit = true;
      goal_changed.notify_all();
      // A motion this node started ends with it (its clients are gone with the master).
      for (const auto& r : runners)
        if (!*r.done) arm.stop();
    }
    publisher.join();
    for (auto& r : runners) r.thread.join();
  }

  bool quitting() {
    std::lock_guard<std::mutex> lock(mutex);
    return quit;
  }

  // ---- published state

  void publish_loop() {
    std::uint64_t seen = 0;
    double read_at = -1;  // one message per read: snapshots change for other reasons too
    auto next_status = std::chrono::steady_clock::now();
    while (!quitting()) {
      const ArmState s = arm.wait_for_update(seen, std::chrono::milliseconds(100));
      if (s.read_time != read_at && s.link_ok && !s.positions.empty()) {
        read_at = s.read_time;
        sensor_msgs::JointState m;
        m.header.stamp = ros::Time::now();
        m.name = info.joints;
        m.position = s.positions;
        m.velocity = s.velocities;
        joint_states.publish(m);
      }
      seen = s.sequence;
      if (std::chrono::steady_clock::now() >= next_status) {
        next_status += std::chrono::seconds(1);
        publish_status(s);
      }
    }
  }

  void publish_status(const ArmState& s) {
    if (s.battery_volts) {
      sensor_msgs::BatteryState b;
      b.header.stamp = ros::Time::now();
      b.voltage = float(*s.battery_volts);
      b.current = b.charge = b.capacity = b.design_capacity = b.percentage = std::nanf("");
      b.power_supply_status = sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_UNKNOWN;
      b.power_supply_health = sensor_msgs::BatteryState::POWER_SUPPLY_HEALTH_UNKNOWN;
      b.power_supply_technology = sensor_msgs::BatteryState::POWER_SUPPLY_TECHNOLOGY_UNKNOWN;
      b.present = true;
      battery.publish(b);
    }
    diagnostic_msgs::DiagnosticArray a;
    a.header.stamp = ros::Time::now();
    diagnostic_msgs::DiagnosticStatus d;
    d.name = fmt::format("armctl_ros: {} arm", info.name);
    d.hardware_id = device.empty() ? "embedded simulator" : device;
    auto kv = [&](std::string key, std::string value) {
      diagnostic_msgs::KeyValue k;
      k.key = std::move(key);
      k.value = std::move(value);
      d.values.push_back(k);
    };
    if (!s.link_ok) {
      d.level = diagnostic_msgs::DiagnosticStatus::ERROR;
      d.message = fmt::format("link lost: {}", s.link_error.empty() ? "nothing read yet" : s.link_error);
    } else if (!s.faults.empty()) {
      d.level = diagnostic_msgs::DiagnosticStatus::ERROR;
      d.message = fmt::format("joint faults: {}", fmt::join(s.faults, "; "));
    } else if (!s.last_error.empty()) {
      d.level = diagnostic_msgs::DiagnosticStatus::WARN;
      d.message = fmt::format("last command failed: {}", s.last_error);
    } else {
      d.level = diagnostic_msgs::DiagnosticStatus::OK;
      d.message = s.job.empty() ? "idle" : fmt::format("running: {}", s.job);
    }
    kv("link", s.link_ok ? "ok" : "lost");
    kv("link error", s.link_error);
    kv("job", s.job);
    kv("last error", s.last_error);
    kv("faults", fmt::format("{}", fmt::join(s.faults, "; ")));
    kv("battery", s.battery_volts ? fmt::format("{:.2f} V", *s.battery_volts) : "");
    // The scene's limits plans are checked with (docs/scene.md "Fence and reduced mode").
    const ArmBridge::Limits limits = arm.limits();
    auto on_off = [](const std::optional<bool>& on) { return !on ? "none" : *on ? "on" : "off"; };
    kv("fence", on_off(limits.fence));
    kv("reduced mode", on_off(limits.reduced_mode));
    {
      std::lock_guard<std::mutex> lock(counters.mutex);
      kv("refused commands", std::to_string(counters.refused));
      kv("last refusal", counters.last_refusal);
      kv("goals succeeded", std::to_string(counters.succeeded));
      kv("goals failed", std::to_string(counters.failed));
      kv("goals canceled", std::to_string(counters.canceled));
      kv("last failure", counters.last_failure);
    }
    a.status.push_back(d);
    diagnostics.publish(a);
  }

  // ---- motions

  // A thread that runs one motion (joined when the node ends; finished ones on the next).
  template <typename F>
  void start_runner(F&& f) {
    std::lock_guard<std::mutex> lock(mutex);
    if (quit) return;
    for (auto it = runners.begin(); it != runners.end();) {
      if (*it->done) {
        it->thread.join();
        it = runners.erase(it);
      } else {
        ++it;
      }
    }
    auto done = std::make_shared<std::atomic<bool>>(false);
    runners.push_back({std::thread([done, f = std::forward<F>(f)]() mutable {
                         f();
                         *done = true;
                       }),
                       done});
  }

  void refuse(GoalHandle& g, const GoalRefusal& r) {
    FollowJointTrajectoryResult result;
    result.error_code = int(r.code);
    result.error_string = r.message;
    counters.refusal(r.message);
    ROS_WARN("trajectory goal rejected: %s", r.message.c_str());
    g.setRejected(result, r.message);
  }

  void on_goal(GoalHandle g) {
    const auto goal = g.getGoal();
    TrajectoryGoal t;
    t.request = request_of(goal->trajectory);
    t.path_tolerance = tolerances_of(goal->path_tolerance);
    t.goal_tolerance = tolerances_of(goal->goal_tolerance);
    t.goal_time_tolerance = goal->goal_time_tolerance.toSec();
    double duration = 0;
    if (auto refused = arm.check(t, &duration)) return refuse(g, *refused);
    // A stamp says when the trajectory was to start: one that has ended already is refused.
    const ros::Time stamp = goal->trajectory.header.stamp;
    if (!stamp.isZero() && stamp + ros::Duration(duration) < ros::Time::now())
      return refuse(g, {GoalError::old_header_timestamp,
                        fmt::format("the trajectory's header stamp {:.3f} s plus its {:.3f} s is in the past (now "
                                    "{:.3f} s): it would have ended already", stamp.toSec(), duration,
                                    ros::Time::now().toSec())});
    // One in the future is when to start; further ahead than the longest trajectory allowed
    // is a mistake (a stamp in another clock, seconds taken for nanoseconds).
    if (!stamp.isZero() && stamp > ros::Time::now() + ros::Duration(kLongestTrajectory))
      return refuse(g, {GoalError::invalid_goal,
                        fmt::format("the trajectory's header stamp {:.3f} s is {:.0f} s in the future (now {:.3f} s); "
                                    "allowed: 0 (start now) or a time at most {:.0f} s ahead",
                                    stamp.toSec(), (stamp - ros::Time::now()).toSec(), ros::Time::now().toSec(),
                                    kLongestTrajectory)});
    g.setAccepted("accepted");
    {
      // Before its runner starts, so that a cancel right after the accept reaches it and an
      // older goal still waiting for its stamp gives way at once.
      std::lock_guard<std::mutex> lock(mutex);
      active_goal = g.getGoalID().id;
      goal_changed.notify_all();
    }
    start_runner([this, g, t, stamp] { run_goal(g, t, stamp); });
  }

  void on_cancel(GoalHandle g) {
    std::lock_guard<std::mutex> lock(mutex);
    const std::string id = g.getGoalID().id;
    if (id == active_goal) {
      canceled_goal = id;
      goal_changed.notify_all();
    }
    if (id == moving_goal) arm.stop();
  }

  // Until the goal's header stamp (now if it has none or it has passed). False if the goal
  // was canceled or preempted by a newer one meanwhile, or the node ends: then nothing moved.
  // True: it is the moving goal from then on.
  bool wait_for_start(const std::string& id, const ros::Time& stamp) {
    std::unique_lock<std::mutex> lock(mutex);
    const auto still_ours = [&] { return !quit && active_goal == id && canceled_goal != id; };
    while (still_ours() && !stamp.isZero() && ros::Time::now() < stamp) {
      // In slices: ROS time may be simulated (use_sim_time) and not run with the wall clock.
      const double left = (stamp - ros::Time::now()).toSec();
      goal_changed.wait_for(lock, std::chrono::duration<double>(std::min(left, 0.05)));
    }
    if (!still_ours()) return false;
    moving_goal = id;
    return true;
  }

  void run_goal(GoalHandle g, const TrajectoryGoal& t, const ros::Time& stamp) {
    const std::string id = g.getGoalID().id;
    if (!wait_for_start(id, stamp)) {
      FollowJointTrajectoryResult result;
      result.error_code = FollowJointTrajectoryResult::SUCCESSFUL;
      result.error_string = "canceled before its header stamp: nothing moved";
      {
        std::lock_guard<std::mutex> c(counters.mutex);
        ++counters.canceled;
      }
      g.setCanceled(result, result.error_string);
      return;
    }
    const MotionOutcome m = arm.follow(t, [&](const Desired& d, const ArmState& s) { feedback(g, t, d, s); });
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (active_goal == id) active_goal.clear();
      if (moving_goal == id) moving_goal.clear();
    }
    FollowJointTrajectoryResult result;
    result.error_string = m.message;
    if (m.stopped) {
      result.error_code = FollowJointTrajectoryResult::SUCCESSFUL;
      {
        std::lock_guard<std::mutex> c(counters.mutex);
        ++counters.canceled;
      }
      g.setCanceled(result, m.message);
    } else if (!m.ok) {
      result.error_code = int(m.code == GoalError::none ? GoalError::invalid_goal : m.code);
      counters.failure(m.message);
      ROS_WARN("trajectory goal aborted: %s", m.message.c_str());
      g.setAborted(result, m.message);
    } else {
      result.error_code = FollowJointTrajectoryResult::SUCCESSFUL;
      {
        std::lock_guard<std::mutex> c(counters.mutex);
        ++counters.succeeded;
      }
      g.setSucceeded(result, m.message);
    }
  }

  int index_of(const std::string& name) const {
    for (std::size_t j = 0; j < info.joints.size(); ++j)
      if (info.joints[j] == name) return int(j);
    return -1;
  }

  void feedback(GoalHandle& g, const TrajectoryGoal& t, const Desired& d, const ArmState& s) {
    if (s.positions.size() != info.joints.size() || d.positions.size() != info.joints.size()) return;
    control_msgs::FollowJointTrajectoryFeedback f;
    f.header.stamp = ros::Time::now();
    f.joint_names = t.request.joint_names;
    for (const auto& n : t.request.joint_names) {
      const int i = index_of(n);
      if (i < 0) return;
      const auto j = std::size_t(i);
      const double v = j < s.velocities.size() ? s.velocities[j] : 0.0;
      f.desired.positions.push_back(d.positions[j]);
      f.desired.velocities.push_back(d.velocities[j]);
      f.actual.positions.push_back(s.positions[j]);
      f.actual.velocities.push_back(v);
      f.error.positions.push_back(d.positions[j] - s.positions[j]);
      f.error.velocities.push_back(d.velocities[j] - v);
    }
    f.desired.time_from_start = f.actual.time_from_start = f.error.time_from_start = ros::Duration(d.t);
    g.publishFeedback(f);
  }

  // The streaming topic: each message replaces the running motion; one without points stops.
  void on_command(const trajectory_msgs::JointTrajectory::ConstPtr& m) {
    if (m->points.empty()) {
      arm.stop();
      return;
    }
    TrajectoryGoal t;
    t.request = request_of(*m);
    if (auto refused = arm.check(t)) {
      counters.refusal(refused->message);
      ROS_WARN("arm_controller/command refused: %s", refused->message.c_str());
      return;
    }
    start_runner([this, t] {
      const MotionOutcome o = arm.follow(t, {});
      if (!o.ok && !o.stopped) {
        counters.failure(o.message);
        ROS_WARN("arm_controller/command failed: %s", o.message.c_str());
      }
    });
  }

  // A servo command refused: counted, and said at most once a second (they come at 50 Hz).
  void servo_refused(const std::string& why) {
    if (why.empty()) return;
    counters.refusal(why);
    ROS_WARN_THROTTLE(1.0, "servo command refused: %s", why.c_str());
  }

  void on_twist(const geometry_msgs::TwistStamped::ConstPtr& m) {
    const std::string& frame = m->header.frame_id;
    const bool tool = frame == info.tool_frame;
    if (!frame.empty() && frame != info.base_frame && !tool)
      return servo_refused(fmt::format("delta_twist_cmds in frame '{}': give it in '{}' (the base) or '{}' (the tool)",
                                       frame, info.base_frame, info.tool_frame));
    const auto& l = m->twist.linear;
    const auto& a = m->twist.angular;
    servo_refused(arm.servo_twist({l.x, l.y, l.z}, {a.x, a.y, a.z}, tool));
  }

  void on_joint_jog(const control_msgs::JointJog::ConstPtr& m) {
    if (m->velocities.empty() && !m->displacements.empty())
      return servo_refused("delta_joint_cmds with displacements only: armctl_ros follows velocities (rad/s, m/s)");
    servo_refused(arm.servo_joints(m->joint_names, m->velocities));
  }

  void on_pose_goal(const geometry_msgs::PoseStamped::ConstPtr& m) {
    if (m->header.frame_id != info.base_frame) {
      const auto why = fmt::format("pose_goal in frame '{}' refused: give it in the arm's base frame '{}'",
                                   m->header.frame_id, info.base_frame);
      counters.refusal(why);
      ROS_WARN("%s", why.c_str());
      return;
    }
    const auto& p = m->pose.position;
    const auto& q = m->pose.orientation;
    std::vector<double> position{p.x, p.y, p.z}, quaternion{q.w, q.x, q.y, q.z};
    start_runner([this, position, quaternion] {
      const MotionOutcome o = arm.move_to(position, quaternion);
      if (!o.ok && !o.stopped) {
        if (o.code != GoalError::none) counters.refusal(o.message);
        else counters.failure(o.message);
        ROS_WARN("pose_goal failed: %s", o.message.c_str());
      }
    });
  }

  // ---- services

  template <typename Response>
  bool answer(Response& res, const MotionOutcome& o, const std::string& done) {
    res.success = o.ok;
    res.message = o.ok ? done : o.message;
    if (!o.ok) {
      if (o.code != GoalError::none) counters.refusal(o.message);
      else counters.failure(o.message);
    }
    return true;
  }

  bool on_stop(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    arm.stop();
    res.success = true;
    res.message = "stopping: a running motion slows down on its path, then every joint holds";
    return true;
  }

  bool on_torque(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
    const bool on = req.data;
    return answer(res, arm.set_torque(on), on ? "torque on: holding where it stands" : "torque off: the arm can be moved by hand");
  }

  bool on_clear_faults(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return answer(res, arm.clear_faults(), "faults cleared: every joint holds where it is and drives again");
  }

  bool on_gripper(armctl_msgs::SetGripper::Request& req, armctl_msgs::SetGripper::Response& res) {
    return answer(res, arm.gripper(req.closed_fraction), fmt::format("gripper at {:.2f} closed", req.closed_fraction));
  }

  // The answering twin of the pose_goal topic: says how it went, the plan and why not.
  bool on_move_to(armctl_msgs::MoveTo::Request& req, armctl_msgs::MoveTo::Response& res) {
    const auto& p = req.pose.position;
    const auto& q = req.pose.orientation;
    const MotionOutcome o = arm.move_to({p.x, p.y, p.z}, {q.w, q.x, q.y, q.z});
    res.kind = o.kind;
    res.duration = o.duration;
    res.targets = o.targets;
    return answer(res, o, "arrived");
  }

  bool on_run_group(armctl_msgs::RunActionGroup::Request& req, armctl_msgs::RunActionGroup::Response& res) {
    return answer(res, arm.run_action_group(req.group, req.times),
                  fmt::format("action group {} started ({} times; 0: until stopped)", req.group, req.times));
  }

  bool on_stop_group(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    return answer(res, arm.stop_action_group(), "action group stopped");
  }

  bool on_set_scene_object(armctl_msgs::SetSceneObject::Request& req, armctl_msgs::SetSceneObject::Response& res) {
    const MotionOutcome o = arm.set_scene_object(req.object);
    res.kind = o.kind;
    return answer(res, o, "the scene holds it: plans are checked against it from now on");
  }

  bool on_set_fence(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
    const bool on = req.data;
    return answer(res, arm.set_fence(on), on ? "fence on: plans and motions are kept inside it" : "fence off");
  }

  bool on_set_reduced_mode(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
    const bool on = req.data;
    return answer(res, arm.set_reduced_mode(on),
                  on ? "reduced mode on: the tool speed cap and joint ranges hold from now on" : "reduced mode off");
  }

  bool on_remove_scene_object(armctl_msgs::RemoveSceneObject::Request& req,
                              armctl_msgs::RemoveSceneObject::Response& res) {
    const MotionOutcome o = arm.remove_scene_object(req.name);
    res.kind = o.kind;
    return answer(res, o, fmt::format("'{}' removed from the scene", req.name));
  }
};

ArmNode::ArmNode(ArmBridge& arm, NodeCounters& counters, const std::string& device)
    : impl_(std::make_unique<Impl>(arm, counters, device)) {}

ArmNode::~ArmNode() = default;

}  // namespace armctl::ros_node

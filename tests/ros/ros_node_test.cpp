// armctl_ros against a real roscore, on both embedded simulators: every test starts its
// own master (a free loopback port, ROS_HOME in a temporary folder) and node, and ends them.
// A ROS client (roscpp, actionlib, tf2_ros) checks what the issue lists: joint_states, a
// five-point goal, refused goals that move nothing, cancel, tf against armctl's FK, a
// master restart, and the device going away (docs/ros.md "Device loss").
#include <fmt/core.h>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <actionlib/client/simple_action_client.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/JointJog.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <trajectory_msgs/JointTrajectory.h>

#include "armctl_msgs/MoveTo.h"
#include "armctl_msgs/RunActionGroup.h"
#include "armctl_msgs/RemoveSceneObject.h"
#include "armctl_msgs/SetGripper.h"
#include "armctl_msgs/SetSceneObject.h"
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2_ros/transform_listener.h>

#include "arm_reference.hpp"
#include "ros_harness.hpp"

namespace armctl::ros_test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;
using Client = actionlib::SimpleActionClient<control_msgs::FollowJointTrajectoryAction>;
using control_msgs::FollowJointTrajectoryGoal;
using control_msgs::FollowJointTrajectoryResult;

const std::string kNode = ARMCTL_BINARY_DIR "/armctl_ros";

// The newest joint_states and how many arrived (and when).
class JointStates {
 public:
  JointStates() {
    ros::NodeHandle nh;
    sub_ = nh.subscribe("/joint_states", 100, &JointStates::on, this);
  }
  sensor_msgs::JointState last() {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_;
  }
  int count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }
  std::vector<ros::Time> stamps() {
    std::lock_guard<std::mutex> lock(mutex_);
    return stamps_;
  }

 private:
  void on(const sensor_msgs::JointState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    last_ = *m;
    ++count_;
    stamps_.push_back(m->header.stamp);
  }
  std::mutex mutex_;
  sensor_msgs::JointState last_;
  int count_ = 0;
  std::vector<ros::Time> stamps_;  // when the node published them (arrivals come in bursts)
  ros::Subscriber sub_;
};

class Diagnostics {
 public:
  Diagnostics() {
    ros::NodeHandle nh;
    sub_ = nh.subscribe("/diagnostics", 10, &Diagnostics::on, this);
  }
  std::vector<diagnostic_msgs::DiagnosticStatus> all() {
    std::lock_guard<std::mutex> lock(mutex_);
    return seen_;
  }

 private:
  void on(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& s : m->status) seen_.push_back(s);
  }
  std::mutex mutex_;
  std::vector<diagnostic_msgs::DiagnosticStatus> seen_;
  ros::Subscriber sub_;
};

std::unique_ptr<Process> start_node(const std::string& arm, const std::vector<std::string>& more = {}) {
  std::vector<std::string> argv{kNode, "_arm:=" + arm, "__name:=armctl_ros"};
  argv.insert(argv.end(), more.begin(), more.end());
  return std::make_unique<Process>(argv, ros_world().dir + "/armctl_ros-" + arm + ".log");
}

// ~move_to's request for a tool pose (x y z, then the quaternion w x y z).
armctl_msgs::MoveTo move_to_pose(const std::vector<double>& pose) {
  armctl_msgs::MoveTo m;
  m.request.pose.position.x = pose[0];
  m.request.pose.position.y = pose[1];
  m.request.pose.position.z = pose[2];
  m.request.pose.orientation.w = pose[3];
  m.request.pose.orientation.x = pose[4];
  m.request.pose.orientation.y = pose[5];
  m.request.pose.orientation.z = pose[6];
  return m;
}

double distance(const std::vector<double>& a, const std::vector<double>& b, std::size_t n) {
  double d = 0;
  for (std::size_t i = 0; i < n; ++i) d = std::max(d, std::abs(a.at(i) - b.at(i)));
  return d;
}

class RosNode : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    ros_world();
    master_ = start_master();  // first: roscpp starts (and registers) with the first spinner
    spinner_ = std::make_unique<ros::AsyncSpinner>(2);
    spinner_->start();
    node_ = start_node(arm());
    states_ = std::make_unique<JointStates>();
    // The first start builds the embedded simulator (ASan makes it slow).
    ASSERT_TRUE(wait_until([&] { return states_->count() > 0; }, 60s)) << node_->log_text();
    joints_ = reference_joints(arm());
    for (const auto& j : joints_) chain_ += j.chain ? 1 : 0;
  }
  void TearDown() override {
    client_.reset();
    states_.reset();
    if (node_) node_->terminate();
    if (master_) master_->terminate();
    spinner_->stop();
  }

  std::string arm() const { return GetParam(); }

  Client& client() {
    if (!client_) {
      client_ = std::make_unique<Client>("/arm_controller/follow_joint_trajectory", true);
      EXPECT_TRUE(client_->waitForServer(ros::Duration(30))) << node_->log_text();
    }
    return *client_;
  }

  std::vector<std::string> chain_names() const {
    std::vector<std::string> out;
    for (const auto& j : joints_)
      if (j.chain) out.push_back(j.name);
    return out;
  }

  // A goal through `offsets` (fractions of each chain joint's range, added to where it
  // stands, reflected to stay inside), one point per `step` s.
  FollowJointTrajectoryGoal goal_through(const std::vector<double>& offsets, double step) {
    const auto here = states_->last().position;
    FollowJointTrajectoryGoal g;
    g.trajectory.joint_names = chain_names();
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      trajectory_msgs::JointTrajectoryPoint p;
      for (std::size_t j = 0; j < chain_; ++j) {
        const auto& l = joints_[j];
        double q = here[j] + offsets[k] * (l.upper - l.lower);
        if (q > l.upper || q < l.lower) q = here[j] - offsets[k] * (l.upper - l.lower);
        p.positions.push_back(q);
      }
      p.time_from_start = ros::Duration(step * double(k + 1));
      g.trajectory.points.push_back(p);
    }
    return g;
  }

  // The arm at rest: three joint_states in a row, each within `tolerance` of the one before.
  bool at_rest(std::chrono::milliseconds timeout, double tolerance = 0.002) {
    std::vector<double> previous;
    int seen = states_->count(), still = 0;
    return wait_until(
        [&] {
          if (states_->count() == seen) return false;
          seen = states_->count();
          const auto now = states_->last().position;
          still = !previous.empty() && distance(now, previous, chain_) < tolerance ? still + 1 : 0;
          previous = now;
          return still >= 3;
        },
        timeout);
  }

  std::unique_ptr<ros::AsyncSpinner> spinner_;
  std::unique_ptr<Process> master_, node_;
  std::unique_ptr<JointStates> states_;
  std::unique_ptr<Client> client_;
  std::vector<ReferenceJoint> joints_;
  std::size_t chain_ = 0;
};

TEST_P(RosNode, PublishesJointStatesWithTheModelsNamesAndTheUrdf) {
  const int before = states_->count();
  ASSERT_TRUE(wait_until([&] { return states_->count() >= before + 20; }, 20s));
  const auto m = states_->last();
  ASSERT_EQ(m.name.size(), joints_.size());
  for (std::size_t j = 0; j < joints_.size(); ++j) EXPECT_EQ(m.name[j], joints_[j].name);
  ASSERT_EQ(m.position.size(), joints_.size());
  ASSERT_EQ(m.velocity.size(), joints_.size());
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    EXPECT_GE(m.position[j], joints_[j].lower - 1e-6) << m.name[j];
    EXPECT_LE(m.position[j], joints_[j].upper + 1e-6) << m.name[j];
    EXPECT_NEAR(m.velocity[j], 0, 1e-6) << "at rest";
  }
  // The rate: ~rate = 50 Hz by default, or the link's pace where that is slower (a read
  // plus the 20 ms between reads); at least 60 % of it on a loaded machine with the
  // sanitizers (bench/ros measures it on an idle one).
  const auto t = states_->stamps();
  const double rate = 19.0 / (t.back() - t[t.size() - 20]).toSec();
  const double read = reference_read_seconds(arm(), 10);
  const double expected = 1.0 / (read + 1.0 / 50);
  std::printf("joint_states of %s: %.1f Hz (a read takes %.1f ms: %.1f Hz expected)\n", arm().c_str(), rate,
              read * 1e3, expected);
  EXPECT_GE(rate, 0.6 * expected);
  EXPECT_LE(rate, 60.0);
  std::string urdf;
  ASSERT_TRUE(ros::param::get("/robot_description", urdf));
  EXPECT_THAT(urdf, HasSubstr("<robot"));
  EXPECT_THAT(urdf, HasSubstr("name=\"" + joints_[0].name + "\""));
}

TEST_P(RosNode, AFivePointGoalSucceedsAndTheArmEndsThere) {
  auto goal = goal_through({0.03, 0.06, 0.02, -0.03, 0.04}, 1.0);
  client().sendGoal(goal);
  ASSERT_TRUE(client().waitForResult(ros::Duration(30)));
  EXPECT_EQ(client().getState(), actionlib::SimpleClientGoalState::SUCCEEDED) << client().getState().getText();
  EXPECT_EQ(client().getResult()->error_code, FollowJointTrajectoryResult::SUCCESSFUL);
  const auto& target = goal.trajectory.points.back().positions;
  // Within 1 deg / 1 mm: the default goal tolerance (0.5 deg, 0.5 mm) and the xArm's 0.24 deg step.
  auto arrived = [&] {
    const auto q = states_->last().position;
    for (std::size_t j = 0; j < chain_; ++j)
      if (std::abs(q[j] - target[j]) > (joints_[j].revolute ? M_PI / 180 : 0.001)) return false;
    return true;
  };
  ASSERT_TRUE(wait_until(arrived, 5s))
      << "at " << ::testing::PrintToString(states_->last().position) << ", asked "
      << ::testing::PrintToString(target);
}

TEST_P(RosNode, BadGoalsAreRejectedWithAClearMessageAndNothingMoves) {
  const auto before = states_->last().position;
  struct Case {
    const char* what;
    FollowJointTrajectoryGoal goal;
    int code;
    const char* says;
  };
  std::vector<Case> cases;
  auto g = goal_through({0.03, 0.06}, 1.0);
  g.trajectory.joint_names[0] = "no_such_joint";
  cases.push_back({"unknown joint", g, FollowJointTrajectoryResult::INVALID_JOINTS, "unknown joint 'no_such_joint'"});
  g = goal_through({0.03, 0.06}, 1.0);
  g.trajectory.points[1].positions[0] = joints_[0].upper + 0.1;
  cases.push_back({"beyond a limit", g, FollowJointTrajectoryResult::INVALID_GOAL, "beyond its limits"});
  g = goal_through({0.03, 0.06, 0.02}, 1.0);
  g.trajectory.points[2].time_from_start = g.trajectory.points[1].time_from_start;
  cases.push_back({"non-increasing times", g, FollowJointTrajectoryResult::INVALID_GOAL, "times must rise"});
  g = goal_through({0.03, 0.06}, 1.0);
  g.trajectory.header.stamp = ros::Time::now() - ros::Duration(100);
  cases.push_back({"ended already", g, FollowJointTrajectoryResult::OLD_HEADER_TIMESTAMP, "it would have ended already"});
  g.trajectory.header.stamp = ros::Time::now() + ros::Duration(4000);
  cases.push_back({"far future", g, FollowJointTrajectoryResult::INVALID_GOAL, "at most 3600 s ahead"});
  for (const auto& c : cases) {
    client().sendGoal(c.goal);
    ASSERT_TRUE(client().waitForResult(ros::Duration(10))) << c.what;
    EXPECT_EQ(client().getState(), actionlib::SimpleClientGoalState::REJECTED) << c.what;
    ASSERT_TRUE(client().getResult()) << c.what;
    EXPECT_EQ(client().getResult()->error_code, c.code) << c.what;
    EXPECT_THAT(client().getResult()->error_string, HasSubstr(c.says)) << c.what;
  }
  // Nothing moved: the next joint_states still read where the arm stood.
  const int seen = states_->count();
  ASSERT_TRUE(wait_until([&] { return states_->count() >= seen + 5; }, 10s));
  EXPECT_LT(distance(states_->last().position, before, joints_.size()), 0.002);
}

TEST_P(RosNode, AHeaderStampInTheFutureIsWhenTheMotionStarts) {
  ASSERT_TRUE(at_rest(10s));
  const auto before = states_->last().position;
  auto moved = [&] { return distance(states_->last().position, before, chain_) > 0.002; };
  // Canceled while it waits for its stamp: nothing moves.
  auto goal = goal_through({0.03}, 1.0);
  goal.trajectory.header.stamp = ros::Time::now() + ros::Duration(30);
  client().sendGoal(goal);
  ASSERT_TRUE(wait_until([&] { return client().getState() == actionlib::SimpleClientGoalState::ACTIVE; }, 10s));
  client().cancelGoal();
  ASSERT_TRUE(client().waitForResult(ros::Duration(10)));
  EXPECT_EQ(client().getState(), actionlib::SimpleClientGoalState::PREEMPTED) << client().getState().getText();
  EXPECT_THAT(client().getState().getText(), HasSubstr("canceled before its header stamp"));
  EXPECT_FALSE(moved());
  // Left alone, it starts at its stamp, not when it was accepted.
  goal.trajectory.header.stamp = ros::Time::now() + ros::Duration(1.5);
  const ros::Time stamp = goal.trajectory.header.stamp;
  client().sendGoal(goal);
  ASSERT_TRUE(wait_until(moved, 20s)) << node_->log_text();
  EXPECT_GE(ros::Time::now().toSec(), stamp.toSec()) << "it moved before its stamp";
  ASSERT_TRUE(client().waitForResult(ros::Duration(30)));
  EXPECT_EQ(client().getState(), actionlib::SimpleClientGoalState::SUCCEEDED) << client().getState().getText();
}

// A path tolerance is one joint's: a tight one on a moving joint aborts the goal naming it;
// the same on a joint that stays where it is leaves the others at the default (5 deg / 5 mm).
TEST_P(RosNode, PathTolerancesAreTakenJointByJoint) {
  ASSERT_TRUE(at_rest(10s));
  std::vector<std::size_t> revolute;  // chain joints; one moves, another stays
  for (std::size_t j = 0; j < chain_; ++j)
    if (joints_[j].revolute) revolute.push_back(j);
  ASSERT_GE(revolute.size(), 2u);
  const std::size_t moving = revolute.front(), still = revolute.back();

  auto tight = [](const std::string& name, double position) {
    control_msgs::JointTolerance t;
    t.name = name;
    t.position = position;
    return t;
  };
  auto goal = goal_through({0.04}, 1.5);
  goal.path_tolerance.push_back(tight(joints_[moving].name, 1e-5));
  client().sendGoal(goal);
  ASSERT_TRUE(client().waitForResult(ros::Duration(30)));
  EXPECT_EQ(client().getState(), actionlib::SimpleClientGoalState::ABORTED) << client().getState().getText();
  EXPECT_EQ(client().getResult()->error_code, FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED);
  EXPECT_THAT(client().getResult()->error_string, HasSubstr("following error on joint " + joints_[moving].name));
  ASSERT_TRUE(at_rest(10s));

  goal = goal_through({0.04}, 1.5);
  for (auto& p : goal.trajectory.points) p.positions[still] = states_->last().position[still];
  goal.path_tolerance.push_back(tight(joints_[still].name, 0.0035));  // 0.2 deg
  client().sendGoal(goal);
  ASSERT_TRUE(client().waitForResult(ros::Duration(30)));
  EXPECT_EQ(client().getState(), actionlib::SimpleClientGoalState::SUCCEEDED) << client().getState().getText();
}

TEST_P(RosNode, CancelHaltsTheArmMidTrajectory) {
  const auto start = states_->last().position;
  auto goal = goal_through({0.25}, 6.0);
  const auto target = goal.trajectory.points[0].positions;
  std::size_t j = 0;  // the joint that moves the most
  for (std::size_t i = 0; i < chain_; ++i)
    if (std::abs(target[i] - start[i]) > std::abs(target[j] - start[j])) j = i;
  const double way = target[j] - start[j];
  client().sendGoal(goal);
  ASSERT_TRUE(wait_until([&] { return (states_->last().position[j] - start[j]) / way > 0.2; }, 15s))
      << node_->log_text();
  client().cancelGoal();
  ASSERT_TRUE(client().waitForResult(ros::Duration(15)));
  EXPECT_EQ(client().getState(), actionlib::SimpleClientGoalState::PREEMPTED) << client().getState().getText();
  ASSERT_TRUE(at_rest(10s));
  const double reached = (states_->last().position[j] - start[j]) / way;
  EXPECT_GT(reached, 0.2);
  EXPECT_LT(reached, 0.9) << "halted well before the end";
  // And it stays there.
  const auto halted = states_->last().position;
  const int seen = states_->count();
  ASSERT_TRUE(wait_until([&] { return states_->count() >= seen + 5; }, 10s));
  EXPECT_LT(distance(states_->last().position, halted, chain_), 0.002);
}

TEST_P(RosNode, TfReachesTheToolFrameAndAgreesWithArmctlsKinematics) {
  Process publisher({"/usr/lib/robot_state_publisher/robot_state_publisher"}, ros_world().dir + "/rsp.log");
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(at_rest(10s));
  std::string error;
  ASSERT_TRUE(buffer.canTransform("base_link", "tool", ros::Time(0), ros::Duration(30), &error))
      << error << "\n" << publisher.log_text();
  // The newest transform after the newest joint_states (the arm is at rest).
  const auto q = states_->last().position;
  const auto t = buffer.lookupTransform("base_link", "tool", ros::Time(0)).transform;
  const auto off = reference_tool_offset(arm());
  tf2::Transform link(tf2::Quaternion(t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w),
                      tf2::Vector3(t.translation.x, t.translation.y, t.translation.z));
  tf2::Transform offset(tf2::Quaternion(off[4], off[5], off[6], off[3]), tf2::Vector3(off[0], off[1], off[2]));
  const tf2::Transform tool = link * offset;
  const auto fk = reference_tool_pose(arm(), q);
  EXPECT_NEAR(tool.getOrigin().x(), fk[0], 1e-3);
  EXPECT_NEAR(tool.getOrigin().y(), fk[1], 1e-3);
  EXPECT_NEAR(tool.getOrigin().z(), fk[2], 1e-3);
  const tf2::Quaternion expected(fk[4], fk[5], fk[6], fk[3]);
  EXPECT_LT(tool.getRotation().angleShortestPath(expected), 0.01);
}

TEST_P(RosNode, SurvivesAMasterRestart) {
  master_->terminate();
  master_ = start_master();
  // A new subscriber on the new master hears the node again, the URDF is there again, and
  // the action server answers.
  states_ = std::make_unique<JointStates>();
  ASSERT_TRUE(wait_until([&] { return states_->count() > 2; }, 30s)) << node_->log_text();
  ASSERT_TRUE(wait_until([] { return ros::param::has("/robot_description"); }, 10s));
  client_.reset();
  client().sendGoal(goal_through({0.02}, 1.0));
  ASSERT_TRUE(client().waitForResult(ros::Duration(30)));
  EXPECT_EQ(client().getState(), actionlib::SimpleClientGoalState::SUCCEEDED) << client().getState().getText();
}


TEST_P(RosNode, AStreamedTrajectoryReplacesTheRunningOne) {
  ros::NodeHandle nh;
  auto command = nh.advertise<trajectory_msgs::JointTrajectory>("/arm_controller/command", 1);
  ASSERT_TRUE(wait_until([&] { return command.getNumSubscribers() > 0; }, 10s));
  const auto start = states_->last().position;
  auto first = goal_through({0.2}, 6.0).trajectory;  // long: replaced before its end
  auto second = goal_through({-0.03}, 1.0).trajectory;
  for (std::size_t j = 0; j < chain_; ++j) second.points[0].positions[j] = start[j] + 0.5 * (second.points[0].positions[j] - start[j]);
  command.publish(first);
  ASSERT_TRUE(wait_until([&] { return distance(states_->last().position, start, chain_) > 0.01; }, 10s));
  // The second one starts where the first was stopped (its first point at 1 s).
  command.publish(second);
  const auto& target = second.points[0].positions;
  ASSERT_TRUE(wait_until([&] { return distance(states_->last().position, target, chain_) < 0.0175; }, 20s))
      << ::testing::PrintToString(states_->last().position) << " " << ::testing::PrintToString(target);
  ASSERT_TRUE(at_rest(10s));
  EXPECT_LT(distance(states_->last().position, target, chain_), 0.0175) << "the first one did not go on";
}

TEST_P(RosNode, APoseGoalInTheBaseFrameMovesTheToolThereAndAnotherFrameIsRefused) {
  ros::NodeHandle nh;
  Diagnostics diagnostics;
  auto pose = nh.advertise<geometry_msgs::PoseStamped>("/pose_goal", 1);
  ASSERT_TRUE(wait_until([&] { return pose.getNumSubscribers() > 0; }, 10s));
  auto q = states_->last().position;
  for (std::size_t j = 0; j < chain_; ++j) q[j] += 0.03 * (joints_[j].upper - joints_[j].lower) * (j % 2 ? -1 : 1);
  const auto target = reference_tool_pose(arm(), q);
  geometry_msgs::PoseStamped m;
  m.header.frame_id = "camera";
  m.pose.position.x = target[0];
  m.pose.position.y = target[1];
  m.pose.position.z = target[2];
  m.pose.orientation.w = target[3];
  m.pose.orientation.x = target[4];
  m.pose.orientation.y = target[5];
  m.pose.orientation.z = target[6];
  const auto before = states_->last().position;
  pose.publish(m);
  ASSERT_TRUE(wait_until(
      [&] {
        for (const auto& d : diagnostics.all())
          for (const auto& kv : d.values)
            if (kv.key == "last refusal" && kv.value.find("frame 'camera'") != std::string::npos) return true;
        return false;
      },
      10s));
  EXPECT_LT(distance(states_->last().position, before, chain_), 0.002) << "nothing moved";
  m.header.frame_id = "base_link";
  pose.publish(m);
  auto tool_at_target = [&] {
    const auto p = reference_tool_pose(arm(), states_->last().position);
    return std::hypot(p[0] - target[0], p[1] - target[1], p[2] - target[2]) < 0.002;
  };
  ASSERT_TRUE(wait_until(tool_at_target, 20s)) << node_->log_text();
}

// The servo mode on MoveIt Servo's topics: the first chain joint jogged at a tenth of its
// velocity limit for a second at 50 Hz moves by about that much and comes to rest when the
// messages stop; a twist in a frame the arm lacks is refused, naming the frames it takes.
TEST_P(RosNode, JointJogMovesAJointWhileItComesAndATwistInAnotherFrameIsRefused) {
  ros::NodeHandle nh;
  Diagnostics diagnostics;
  auto jog = nh.advertise<control_msgs::JointJog>("/armctl_ros/delta_joint_cmds", 10);
  auto twist = nh.advertise<geometry_msgs::TwistStamped>("/armctl_ros/delta_twist_cmds", 10);
  ASSERT_TRUE(wait_until([&] { return jog.getNumSubscribers() > 0 && twist.getNumSubscribers() > 0; }, 10s));
  const auto before = states_->last().position;
  const auto& j0 = joints_[0];
  // Toward the middle of its range, so that the end of the range does not slow it.
  const double direction = before[0] < 0.5 * (j0.lower + j0.upper) ? 1.0 : -1.0;
  const double speed = 0.1 * j0.velocity;
  control_msgs::JointJog m;
  m.joint_names = {j0.name};
  m.velocities = {direction * speed};
  const auto end = std::chrono::steady_clock::now() + 1s;
  while (std::chrono::steady_clock::now() < end) {
    m.header.stamp = ros::Time::now();
    jog.publish(m);
    std::this_thread::sleep_for(20ms);  // the publisher's rate, as a joystick driver's
  }
  ASSERT_TRUE(at_rest(10s)) << node_->log_text();
  const double moved = (states_->last().position[0] - before[0]) * direction;
  EXPECT_GT(moved, 0.5 * speed) << node_->log_text();
  EXPECT_LT(moved, 1.6 * speed);

  geometry_msgs::TwistStamped t;
  t.header.frame_id = "camera";
  t.twist.linear.x = 0.01;
  twist.publish(t);
  ASSERT_TRUE(wait_until(
      [&] {
        for (const auto& d : diagnostics.all())
          for (const auto& kv : d.values)
            if (kv.key == "last refusal" && kv.value.find("delta_twist_cmds in frame 'camera'") != std::string::npos)
              return true;
        return false;
      },
      10s));
}

TEST_P(RosNode, ServicesStopTorqueGripperAndActionGroups) {
  ros::NodeHandle nh;
  auto stop = nh.serviceClient<std_srvs::Trigger>("/armctl_ros/stop");
  auto torque = nh.serviceClient<std_srvs::SetBool>("/armctl_ros/set_torque");
  auto gripper = nh.serviceClient<armctl_msgs::SetGripper>("/armctl_ros/gripper");
  auto group = nh.serviceClient<armctl_msgs::RunActionGroup>("/armctl_ros/run_action_group");
  ASSERT_TRUE(gripper.waitForExistence(ros::Duration(10)));
  std_srvs::Trigger t;
  ASSERT_TRUE(stop.call(t));
  EXPECT_TRUE(t.response.success);
  std_srvs::SetBool b;
  b.request.data = true;
  ASSERT_TRUE(torque.call(b));
  EXPECT_TRUE(b.response.success) << b.response.message;
  auto clear = nh.serviceClient<std_srvs::Trigger>("/armctl_ros/clear_faults");
  std_srvs::Trigger c;
  ASSERT_TRUE(clear.call(c));
  EXPECT_TRUE(c.response.success) << c.response.message;  // nothing held on either arm: cleared

  armctl_msgs::SetGripper g;
  g.request.closed_fraction = 1.5;
  ASSERT_TRUE(gripper.call(g));
  EXPECT_FALSE(g.response.success);
  EXPECT_THAT(g.response.message, HasSubstr("0 (open) to 1 (closed)"));
  const std::size_t finger = joints_.size() - 1;
  const double from = states_->last().position[finger];
  g.request.closed_fraction = 0.3;
  ASSERT_TRUE(gripper.call(g));
  EXPECT_TRUE(g.response.success) << g.response.message;
  EXPECT_GT(std::abs(states_->last().position[finger] - from), 1e-3) << "the gripper moved";

  armctl_msgs::RunActionGroup r;
  r.request.group = 255;
  ASSERT_TRUE(group.call(r));
  EXPECT_FALSE(r.response.success);
  EXPECT_THAT(r.response.message, HasSubstr("0..254"));
  r.request.group = 1;
  r.request.times = 1;
  ASSERT_TRUE(group.call(r));
  if (arm() == std::string("scara")) {
    EXPECT_FALSE(r.response.success);
    EXPECT_THAT(r.response.message, HasSubstr("Robot Commands board"));
  }
}

// The planning scene's services: a ball put where a pose lies refuses a move there, naming it;
// a bad object is refused naming its key; removed, the same move runs.
TEST_P(RosNode, SceneObjectsAddedAndRemovedByServiceAreWhatMovesAreCheckedAgainst) {
  ros::NodeHandle nh;
  auto set = nh.serviceClient<armctl_msgs::SetSceneObject>("/armctl_ros/scene/set_object");
  auto remove = nh.serviceClient<armctl_msgs::RemoveSceneObject>("/armctl_ros/scene/remove_object");
  auto move_to = nh.serviceClient<armctl_msgs::MoveTo>("/armctl_ros/move_to");
  ASSERT_TRUE(set.waitForExistence(ros::Duration(10)));
  auto q = states_->last().position;
  for (std::size_t j = 0; j < chain_; ++j) q[j] += 0.03 * (joints_[j].upper - joints_[j].lower) * (j % 2 ? -1 : 1);
  const auto target = reference_tool_pose(arm(), q);

  armctl_msgs::SetSceneObject o;
  o.request.object = R"({"name": "ball", "sphere": {"radius": -3}, "at": [0, 0, 0]})";
  ASSERT_TRUE(set.call(o));
  EXPECT_FALSE(o.response.success);
  EXPECT_EQ(o.response.kind, "invalid config");
  EXPECT_THAT(o.response.message, HasSubstr("sphere.radius"));
  o.request.object = fmt::format(R"({{"name": "ball", "sphere": {{"radius": 25}}, "at": [{:.1f}, {:.1f}, {:.1f}]}})",
                                 target[0] * 1e3, target[1] * 1e3, target[2] * 1e3);
  ASSERT_TRUE(set.call(o));
  EXPECT_TRUE(o.response.success) << o.response.message;

  armctl_msgs::MoveTo m = move_to_pose(target);
  const auto before = states_->last().position;
  ASSERT_TRUE(move_to.call(m));
  EXPECT_FALSE(m.response.success);
  EXPECT_THAT(m.response.message, HasSubstr("sphere 'ball'"));
  EXPECT_LT(distance(states_->last().position, before, chain_), 0.002) << "nothing moved";

  armctl_msgs::RemoveSceneObject r;
  r.request.name = "nothere";
  ASSERT_TRUE(remove.call(r));
  EXPECT_FALSE(r.response.success);
  EXPECT_THAT(r.response.message, HasSubstr("the scene holds: ball"));
  r.request.name = "ball";
  ASSERT_TRUE(remove.call(r));
  EXPECT_TRUE(r.response.success) << r.response.message;
  ASSERT_TRUE(move_to.call(m));
  EXPECT_TRUE(m.response.success) << m.response.message;
}

INSTANTIATE_TEST_SUITE_P(BothArms, RosNode, ::testing::Values("xarm", "scara"));

// The SCARA's simulator as its own process, reached over a unix socket: killing it is the
// device going away. The node reports it in diagnostics at once, then exits with a clear
// error after ~link_timeout (the launch files respawn it, which opens the device again).
// Each arm's simulator as its own process (the SCARA's joint bus on a unix socket, the
// xArm's board on a pty), killed while the node reads it.
// The fence and reduced mode's services (docs/ros.md, docs/scene.md "Fence and reduced
// mode"): the node started with a scene file whose fence the move crosses refuses it before
// anything moves, names the fence and shows it in /diagnostics; switched off by ~set_fence the
// same move runs; ~set_reduced_mode switches the file's reduced mode.
TEST_P(RosNode, TheFenceSwitchedByServiceIsWhatMovesAreCheckedAgainst) {
  const auto here = states_->last().position;
  auto q = here;
  for (std::size_t j = 0; j < chain_; ++j) q[j] += 0.03 * (joints_[j].upper - joints_[j].lower) * (j % 2 ? -1 : 1);
  const auto from = reference_tool_pose(arm(), here);
  const auto target = reference_tool_pose(arm(), q);
  // The fence cuts the axis along which the tool travels most, halfway.
  std::size_t axis = 0;
  for (std::size_t i = 1; i < 3; ++i)
    if (std::abs(target[i] - from[i]) > std::abs(target[axis] - from[axis])) axis = i;
  double low[3], high[3];
  for (std::size_t i = 0; i < 3; ++i) {
    low[i] = (from[i] - 1) * 1e3;
    high[i] = (from[i] + 1) * 1e3;
  }
  const double mid = 0.5 * (from[axis] + target[axis]) * 1e3;
  (target[axis] > from[axis] ? high : low)[axis] = mid;
  const std::string file = fmt::format("{}/fence-{}-{}.json", ros_world().dir, arm(), ::getpid());
  std::FILE* f = std::fopen(file.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs(fmt::format(R"({{"fence": {{"min": [{:.1f}, {:.1f}, {:.1f}], "max": [{:.1f}, {:.1f}, {:.1f}]}},
      "reduced": {{"tool_speed": 50, "on": false}}}})",
                         low[0], low[1], low[2], high[0], high[1], high[2])
                 .c_str(),
             f);
  std::fclose(f);
  node_->terminate();
  states_ = std::make_unique<JointStates>();
  // A start-up switch that cannot be taken ends the node at once, naming it.
  {
    auto bad = start_node(arm(), {"_scene:=" + file, "_fence:=maybe"});
    const auto status = bad->wait_exit(60s);
    ASSERT_TRUE(status) << bad->log_text();
    EXPECT_NE(*status, 0);
    EXPECT_THAT(bad->log_text(), HasSubstr("parameter ~fence is not allowed: true or false"));
    // (A private parameter given at start stays on the master after the node ends.)
    ros::NodeHandle().deleteParam("/armctl_ros/fence");
  }
  // Reduced mode, off in the file, switched on from the start.
  node_ = start_node(arm(), {"_scene:=" + file, "_reduced_mode:=true"});
  ASSERT_TRUE(wait_until([&] { return states_->count() > 0; }, 60s)) << node_->log_text();
  Diagnostics diagnostics;

  ros::NodeHandle nh;
  auto set_fence = nh.serviceClient<std_srvs::SetBool>("/armctl_ros/set_fence");
  auto set_reduced = nh.serviceClient<std_srvs::SetBool>("/armctl_ros/set_reduced_mode");
  auto move_to = nh.serviceClient<armctl_msgs::MoveTo>("/armctl_ros/move_to");
  ASSERT_TRUE(set_fence.waitForExistence(ros::Duration(10)));
  armctl_msgs::MoveTo m = move_to_pose(target);
  const auto before = states_->last().position;
  ASSERT_TRUE(move_to.call(m));
  EXPECT_FALSE(m.response.success);
  EXPECT_THAT(m.response.message, HasSubstr("would leave the fence"));
  EXPECT_LT(distance(states_->last().position, before, chain_), 0.002) << "nothing moved";
  auto shown = [&](const std::string& key, const std::string& value) {
    for (const auto& d : diagnostics.all())
      for (const auto& kv : d.values)
        if (kv.key == key && kv.value == value) return true;
    return false;
  };
  EXPECT_TRUE(wait_until([&] { return shown("fence", "on") && shown("reduced mode", "on"); }, 5s));

  std_srvs::SetBool b;
  b.request.data = false;
  ASSERT_TRUE(set_fence.call(b));
  EXPECT_TRUE(b.response.success) << b.response.message;
  ASSERT_TRUE(set_reduced.call(b));
  EXPECT_TRUE(b.response.success) << b.response.message;
  EXPECT_TRUE(wait_until([&] { return shown("fence", "off") && shown("reduced mode", "off"); }, 5s));
  ASSERT_TRUE(move_to.call(m));
  EXPECT_TRUE(m.response.success) << m.response.message;
  std::remove(file.c_str());
}

class RosNodeDevice : public ::testing::TestWithParam<const char*> {};

TEST_P(RosNodeDevice, ReportsALostDeviceThenExitsWithAClearError) {
  const std::string arm = GetParam();
  const auto& w = ros_world();
  auto master = start_master();
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const std::string path = w.dir + "/" + arm + (arm == "scara" ? ".sock" : ".pty");
  const std::vector<std::string> command =
      arm == "scara" ? std::vector<std::string>{ARMCTL_BINARY_DIR "/armctl", "sim", "scara", "--listen", path}
                     : std::vector<std::string>{ARMCTL_BINARY_DIR "/armctl", "sim", "xarm", "--link", path};
  Process sim(command, w.dir + "/sim-" + arm + ".log");
  ASSERT_TRUE(wait_until([&] { return access(path.c_str(), F_OK) == 0; }, 30s)) << sim.log_text();
  auto node = start_node(arm, {"_device:=" + std::string(arm == "scara" ? "unix:" : "serial:") + path,
                               "_link_timeout:=3"});
  JointStates states;
  Diagnostics diagnostics;
  ASSERT_TRUE(wait_until([&] { return states.count() > 0; }, 60s)) << node->log_text();

  sim.kill_now();
  ASSERT_TRUE(wait_until(
      [&] {
        for (const auto& d : diagnostics.all())
          if (d.level == diagnostic_msgs::DiagnosticStatus::ERROR && d.message.find("link lost") != std::string::npos)
            return true;
        return false;
      },
      20s))
      << node->log_text();
  const auto code = node->wait_exit(30s);
  ASSERT_TRUE(code.has_value()) << node->log_text();
  EXPECT_EQ(*code, 2);
  EXPECT_THAT(node->log_text(), HasSubstr("device lost"));
  spinner.stop();
}

INSTANTIATE_TEST_SUITE_P(BothArms, RosNodeDevice, ::testing::Values("xarm", "scara"));

}  // namespace
}  // namespace armctl::ros_test

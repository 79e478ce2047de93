// armctl_ros against a real rosmaster, on both embedded simulators in step with the wall
// clock (docs/benchmarks.md "ROS"):
//   ros_joint_states_<arm>        joint_states a second with ~rate 0 (a read as soon as the
//                                 last one answered), against the link's refresh floor: one
//                                 read's time measured on the same simulator in this run
//   ros_following_error_<arm>     a five-point FollowJointTrajectory goal: the largest
//                                 |desired - actual| of the revolute joints in its feedback,
//                                 against the same trajectory streamed by the motion
//                                 executor directly (no ROS), each read against the plan
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include <actionlib/client/simple_action_client.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "../../tests/ros/arm_reference.hpp"
#include "../../tests/ros/ros_harness.hpp"
#include "direct_motion.hpp"

namespace {

using namespace armctl;
using namespace std::chrono_literals;
using Client = actionlib::SimpleActionClient<control_msgs::FollowJointTrajectoryAction>;

// joint_states' stamps (when the node published them: arrivals come in bursts).
struct Counter {
  std::mutex mutex;
  std::vector<ros::Time> arrivals;
  void on(const sensor_msgs::JointState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    arrivals.push_back(m->header.stamp);
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(mutex);
    return arrivals.size();
  }
};

// Five points through a few per cent of each chain joint's range, one a second.
ros_node::TrajectoryRequest five_points(const std::string& arm) {
  const auto joints = ros_test::reference_joints(arm);
  const auto here = ros_bench::start_positions(arm);
  ros_node::TrajectoryRequest r;
  for (const auto& j : joints)
    if (j.chain) r.joint_names.push_back(j.name);
  const double offsets[] = {0.03, 0.06, 0.02, -0.03, 0.04};
  for (int k = 0; k < 5; ++k) {
    ros_node::TrajectoryPoint p;
    p.time = k + 1.0;
    for (std::size_t j = 0; j < r.joint_names.size(); ++j) {
      const double range = joints[j].upper - joints[j].lower;
      double q = here[j] + offsets[k] * range;
      if (q > joints[j].upper || q < joints[j].lower) q = here[j] - offsets[k] * range;
      p.positions.push_back(q);
    }
    r.points.push_back(p);
  }
  return r;
}

bool bench_arm(const std::string& arm) {
  // About a second of reads on the same simulator, before the node runs: one read's time
  // is the link's floor.
  const double floor = 1.0 / ros_test::reference_read_seconds(arm, arm == "xarm" ? 5000 : 20);
  auto master = ros_test::start_master();
  ros_test::Process node({ARMCTL_BINARY_DIR "/armctl_ros", "_arm:=" + arm, "_rate:=0", "__name:=armctl_ros"},
                         ros_test::ros_world().dir + "/armctl_ros-" + arm + ".log");
  ros::NodeHandle nh;
  Counter counter;
  auto sub = nh.subscribe("/joint_states", 1000, &Counter::on, &counter);
  if (!ros_test::wait_until([&] { return counter.count() > 10; }, 60s)) {
    std::fprintf(stderr, "no joint_states from the %s node:\n%s\n", arm.c_str(), node.log_text().c_str());
    return false;
  }
  const std::size_t first = counter.count();
  const auto window = std::chrono::steady_clock::now() + 2s;  // two seconds of them
  ros_test::wait_until([&] { return std::chrono::steady_clock::now() >= window; }, 3s);
  double rate = 0;
  {
    std::lock_guard<std::mutex> lock(counter.mutex);
    const auto& t = counter.arrivals;
    rate = double(t.size() - 1 - first) / (t.back() - t[first]).toSec();
  }
  std::printf("BENCH ros_joint_states_%s %.1f Hz limit %.1f ratio %.3f\n", arm.c_str(), rate, floor, rate / floor);

  const auto request = five_points(arm);
  control_msgs::FollowJointTrajectoryGoal goal;
  goal.trajectory.joint_names = request.joint_names;
  for (const auto& p : request.points) {
    trajectory_msgs::JointTrajectoryPoint q;
    q.positions = p.positions;
    q.time_from_start = ros::Duration(p.time);
    goal.trajectory.points.push_back(q);
  }
  const auto joints = ros_test::reference_joints(arm);
  Client client("/arm_controller/follow_joint_trajectory", true);
  if (!client.waitForServer(ros::Duration(30))) {
    std::fprintf(stderr, "no action server from the %s node within 30 s:\n%s\n", arm.c_str(), node.log_text().c_str());
    return false;
  }
  std::mutex mutex;
  double worst = 0;
  client.sendGoal(goal, Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                  [&](const control_msgs::FollowJointTrajectoryFeedbackConstPtr& f) {
                    std::lock_guard<std::mutex> lock(mutex);
                    for (std::size_t i = 0; i < f->joint_names.size(); ++i)
                      for (const auto& j : joints)
                        if (j.name == f->joint_names[i] && j.revolute)
                          worst = std::max(worst, std::abs(f->error.positions[i]));
                  });
  if (!client.waitForResult(ros::Duration(60)) ||
      client.getState() != actionlib::SimpleClientGoalState::SUCCEEDED) {
    std::fprintf(stderr, "the %s goal did not succeed: %s\n", arm.c_str(), client.getState().getText().c_str());
    return false;
  }
  node.terminate();
  const double direct = ros_bench::direct_following_error(arm, request);
  std::lock_guard<std::mutex> lock(mutex);
  std::printf("BENCH ros_following_error_%s %.3f deg limit %.3f ratio %.3f\n", arm.c_str(), worst * 180 / M_PI,
              direct * 180 / M_PI, direct > 0 ? worst / direct : 0.0);
  return true;
}

}  // namespace

int main() {
  ros_test::ros_world();
  auto master = ros_test::start_master();  // roscpp starts with the spinner
  ros::AsyncSpinner spinner(2);
  spinner.start();
  master.reset();
  bool ok = true;
  for (const char* arm : {"xarm", "scara"}) ok = bench_arm(arm) && ok;
  spinner.stop();
  return ok ? 0 : 1;
}

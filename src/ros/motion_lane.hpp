// The one lane every motion of the node goes through (trajectory goals, the streamed
// JointTrajectory topic, pose goals, the gripper): a new motion replaces the running one.
// The running job gets the worker's stop (the executor slows down on the path and the arm
// halts), then the new one is queued on the arm worker, so at most one runs and none waits
// behind another.
#pragma once

#include <future>
#include <mutex>
#include <string>

#include "session/arm_worker.hpp"

namespace armctl::ros_node {

class MotionLane {
 public:
  explicit MotionLane(session::ArmWorker& worker) : worker_(worker) {}

  // Stops what runs (and waits until it has ended), then queues `job`.
  std::shared_future<Status> replace(std::string what, session::ArmWorker::Job job);
  // Stops what runs; returns at once.
  void stop();

 private:
  session::ArmWorker& worker_;
  std::mutex mutex_;  // one replace at a time
  std::shared_future<Status> current_;
};

}  // namespace armctl::ros_node

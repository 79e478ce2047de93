#include "ros/motion_lane.hpp"

#include <chrono>

namespace armctl::ros_node {

std::shared_future<Status> MotionLane::replace(std::string what, session::ArmWorker::Job job) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (current_.valid() && current_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    worker_.command(arm::MotionCommand::stop);
    current_.wait();
  }
  // Behind: the worker may still be halting the arm after the stopped job.
  current_ = worker_.run(std::move(what), std::move(job), true).share();
  return current_;
}

void MotionLane::stop() { worker_.command(arm::MotionCommand::stop); }

}  // namespace armctl::ros_node

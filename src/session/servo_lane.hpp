// Servo commands from callers that share an arm worker (the ROS node's Twist and joint-jog
// topics, the dashboard's hold-to-jog buttons) into one servo session (arm/run_servo.hpp):
// the first command starts a job on the worker that runs the servo loop; later commands go
// to its input; once none has come for `idle_end` and the arm is at rest, the job ends and
// the worker goes back to reading positions. A worker stop (a stop button, a ROS stop
// service, a newer motion) ends it at rest. One place for both apps: they only turn their
// messages into arm::ServoCommand.
#pragma once

#include <future>
#include <memory>
#include <mutex>
#include <string>

#include "arm/run_servo.hpp"
#include "session/arm_worker.hpp"

namespace armctl::session {

class ServoLane {
 public:
  explicit ServoLane(ArmWorker& worker, arm::ServoOptions options = {},
                     Duration idle_end = std::chrono::seconds(1));
  ~ServoLane();  // ends the session at rest

  // Follows `command` (starting the session if none runs). Errors: a bad command (invalid
  // argument, naming what), the worker busy with another job (detail JobRefused::busy), the
  // last session's error when it failed (a following error: detail FollowingError).
  Status send(arm::ServoCommand command);
  // Ends the session at rest (the arm slows down, then the job returns).
  void finish();
  bool running() const;
  // The last cycle of the running (or last) session.
  arm::ServoStatus status() const;

 private:
  struct Session;
  ArmWorker& worker_;
  arm::ServoOptions options_;
  Duration idle_end_;
  mutable std::mutex mutex_;
  std::shared_ptr<Session> session_;
  std::future<Status> job_;
};

}  // namespace armctl::session

// armctl.Servo: the servo mode (arm/run_servo.hpp) for Python, made by Arm.servo() and used as
// a context manager: the arm follows the commands sent to it (twists, joint velocities,
// targets, the gripper) from a thread of its own until the block ends, where it comes to rest
// (also on an exception or Ctrl-C). The session holds the arm's turn: other threads' calls on
// the Arm wait for it to end, and this thread's raise armctl.Error (docs/python.md).
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "arm/arm.hpp"
#include "arm/run_servo.hpp"
#include "bindings.hpp"
#include "python_support.hpp"

namespace armctl::python {

class PyServo {
 public:
  PyServo(arm::Arm& arm, DeviceGate& gate, arm::ServoOptions options);
  ~PyServo();

  void start();                            // __enter__
  void finish(bool raise_errors = true);  // __exit__: to rest, the thread joined
  void send(arm::ServoCommand command);
  py::dict status() const;
  const arm::ArmModel& model() const { return arm_.model(); }

  static void define(py::module_& m);

 private:
  void check_running() const;

  arm::Arm& arm_;
  DeviceGate& gate_;
  arm::ServoOptions options_;
  arm::ServoInput input_;
  std::optional<DeviceGate::Turn> turn_;
  std::thread thread_;
  mutable std::mutex mutex_;  // guards what the loop's thread writes below
  arm::ServoStatus status_;
  std::optional<Result<arm::ServoReport>> result_;
};

// The options of Arm.servo(), checked (armctl.Error naming the value and what is allowed).
arm::ServoOptions servo_options(double speed, double timeout, double max_linear_speed, double max_angular_speed);

}  // namespace armctl::python

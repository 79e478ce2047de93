#include "servo_bindings.hpp"

#include <cmath>

#include <fmt/format.h>
#include <pybind11/stl.h>

namespace armctl::python {

namespace {

using namespace pybind11::literals;

Eigen::Vector3d vector3(const std::vector<double>& v, const char* what) {
  if (v.size() != 3)
    raise(ErrorKind::invalid_argument, fmt::format("{} has {} values: give x, y, z", what, v.size()));
  return {v[0], v[1], v[2]};
}

arm::ServoFrame frame_of(const std::string& frame) {
  if (frame == "base") return arm::ServoFrame::base;
  if (frame == "tool") return arm::ServoFrame::tool;
  raise(ErrorKind::invalid_argument, fmt::format("frame '{}' is not allowed: 'base' or 'tool'", frame));
}

Duration seconds_of(double s, const char* what, double most) {
  if (!std::isfinite(s) || s <= 0 || s > most)
    raise(ErrorKind::invalid_argument, fmt::format("{} {} s is not allowed: above 0 up to {} s", what, s, most));
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s));
}

}  // namespace

PyServo::PyServo(arm::Arm& arm, DeviceGate& gate, arm::ServoOptions options)
    : arm_(arm), gate_(gate), options_(std::move(options)), input_(arm.model()) {}

PyServo::~PyServo() {
  if (thread_.joinable()) finish(false);
}

void PyServo::start() {
  if (turn_ || result_) raise(ErrorKind::invalid_argument, "this servo session has already started: make a new one with arm.servo()");
  turn_.emplace(gate_.enter());
  gate_.set_session("a servo session (with arm.servo())");
  options_.before_cycle = [this](TimePoint) {
    // arm.stop() or close() from another thread ends the session at rest.
    if (gate_.stop_asked() || gate_.closing()) input_.finish();
  };
  options_.on_cycle = [this](const arm::ServoStatus& s) {
    std::lock_guard lock(mutex_);
    status_ = s;
  };
  thread_ = std::thread([this] {
    auto r = arm::run_servo(arm_, input_, options_);
    std::lock_guard lock(mutex_);
    result_ = std::move(r);
  });
}

void PyServo::finish(bool raise_errors) {
  input_.finish();
  if (thread_.joinable()) {
    py::gil_scoped_release nogil;
    thread_.join();
  }
  gate_.set_session(nullptr);
  turn_.reset();
  if (raise_errors && result_ && !result_->ok()) raise(result_->error());
}

void PyServo::check_running() const {
  std::lock_guard lock(mutex_);
  if (!turn_) raise(ErrorKind::invalid_argument, "the servo session is not running: use it in a with block (with arm.servo() as s:)");
  if (result_) {
    if (!result_->ok()) raise(result_->error());
    raise(ErrorKind::invalid_argument, "the servo session has ended (arm.stop() or close() was called)");
  }
}

void PyServo::send(arm::ServoCommand command) {
  check_running();
  must(input_.send(std::move(command)));
}

py::dict PyServo::status() const {
  arm::ServoStatus s;
  {
    std::lock_guard lock(mutex_);
    s = status_;
  }
  py::dict d;
  d["elapsed"] = std::chrono::duration<double>(s.elapsed).count();
  d["positions"] = s.positions;
  d["velocities"] = s.velocities;
  d["scale"] = s.scale;
  d["slowdown"] = std::string(arm::to_string(s.slowdown));
  d["detail"] = s.detail;
  d["commanded"] = s.commanded;
  d["at_rest"] = s.at_rest;
  d["commands"] = s.commands;
  return d;
}

void PyServo::define(py::module_& m) {
  py::class_<PyServo>(m, "Servo",
                      "A servo session (Arm.servo()): the arm follows the commands sent while the with block runs, each\n"
                      "replacing the last, and slows to rest when they stop coming for `timeout` s, at the block's end,\n"
                      "on an exception or Ctrl-C (docs/servo.md).")
      .def("__enter__", [](PyServo& s) -> PyServo& { s.start(); return s; }, py::return_value_policy::reference)
      .def("__exit__", [](PyServo& s, py::object type, py::object, py::object) { s.finish(type.is_none()); })
      .def(
          "twist",
          [](PyServo& s, const std::vector<double>& linear, const std::vector<double>& angular,
             const std::string& frame) {
            s.send(arm::ServoCommand{arm::ToolTwist{vector3(linear, "linear"), vector3(angular, "angular"), frame_of(frame)},
                                     std::nullopt});
          },
          "linear"_a = std::vector<double>{0, 0, 0}, "angular"_a = std::vector<double>{0, 0, 0}, "frame"_a = "base",
          "Moves the tool at `linear` m/s and turns it at `angular` rad/s (x, y, z) in the 'base' or 'tool' frame.")
      .def(
          "joint_velocities",
          [](PyServo& s, const std::vector<double>& values) {
            s.send(arm::ServoCommand{arm::JointVelocities{values}, std::nullopt});
          },
          "values"_a, "Every joint's velocity (rad/s or m/s, the model's order; the gripper's is ignored).")
      .def(
          "joint_targets",
          [](PyServo& s, const std::vector<std::optional<double>>& values) {
            s.send(arm::ServoCommand{arm::JointTargets{values}, std::nullopt});
          },
          "values"_a, "Where the joints should go (SI, one per joint, None keeps one still); beyond a limit: to the limit.")
      .def(
          "pose_target",
          [](PyServo& s, const std::vector<double>& position, std::optional<double> roll, std::optional<double> pitch,
             std::optional<double> yaw) {
            arm::CartesianGoal g;
            g.position = vector3(position, "position");
            g.roll = roll;
            g.pitch = pitch;
            g.yaw = yaw;
            s.send(arm::ServoCommand{arm::PoseTarget{g}, std::nullopt});
          },
          "position"_a, "roll"_a = py::none(), "pitch"_a = py::none(), "yaw"_a = py::none(),
          "Where the tool should go (m; rad), reached by the nearest IK solution; no orientation: the tool's.")
      .def(
          "gripper",
          [](PyServo& s, double closed_fraction) {
            s.send(arm::ServoCommand{arm::ToolTwist{}, closed_fraction});
          },
          "closed_fraction"_a, "The gripper to 0 = open .. 1 = closed (and the arm still).")
      .def(
          "stop", [](PyServo& s) { s.send(arm::ServoCommand{}); },
          "The arm slows to rest and holds (the session goes on).")
      .def_property_readonly("status", &PyServo::status,
                             "The last cycle: {'positions', 'velocities' (SI), 'scale', 'slowdown' ('none', 'joint limit',\n"
                             "'singularity', 'collision', 'unreachable', 'command timeout'), 'detail', 'commanded', 'at_rest',\n"
                             "'commands', 'elapsed'}.");
}

arm::ServoOptions servo_options(double speed, double timeout, double max_linear_speed, double max_angular_speed) {
  if (!(speed > 0 && speed <= 1)) raise(ErrorKind::invalid_argument, fmt::format("speed {} is not allowed: above 0 up to 1", speed));
  if (!(max_linear_speed > 0 && max_linear_speed <= 2) || !(max_angular_speed > 0 && max_angular_speed <= 10))
    raise(ErrorKind::invalid_argument,
          fmt::format("max_linear_speed {} m/s and max_angular_speed {} rad/s are not allowed: above 0 up to 2 m/s and "
                      "10 rad/s",
                      max_linear_speed, max_angular_speed));
  arm::ServoOptions o;
  o.speed = speed;
  o.command_timeout = seconds_of(timeout, "timeout", 10);
  o.max_linear_speed = max_linear_speed;
  o.max_angular_speed = max_angular_speed;
  return o;
}

}  // namespace armctl::python

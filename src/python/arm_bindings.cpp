// armctl.Arm: the Arm API (arm/arm.hpp) and host-planned motion (arm/motion_planning.hpp,
// arm/motion_executor.hpp) for Python. SI units and the C++ names; every value is checked
// by the C++ layers before anything moves. Device I/O runs with the GIL released; Ctrl-C
// stops the arm, then raises KeyboardInterrupt. One Arm serves several Python threads, one
// call at a time (DeviceGate); close() stops what runs, then ends the device (docs/python.md).
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arm/avoid_path.hpp"
#include "arm/plan_moves.hpp"
#include "arm/run_motion.hpp"
#include "program/program_load.hpp"
#include "program/program_plan.hpp"
#include "program/program_runner.hpp"
#include "bindings.hpp"
#include "files/action_group_file.hpp"
#include "python_support.hpp"
#include "scene/scene.hpp"
#include "servo_bindings.hpp"
#include "session/arm_session.hpp"

namespace armctl::python {

namespace {

using Array = py::array_t<double>;

Array to_array(const std::vector<double>& v) {
  Array a(static_cast<py::ssize_t>(v.size()));
  auto m = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < v.size(); ++i) m(static_cast<py::ssize_t>(i)) = v[i];
  return a;
}

Array to_array(const Eigen::VectorXd& v) {
  std::vector<double> out(v.data(), v.data() + v.size());
  return to_array(out);
}

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

Duration duration_of(double s, const char* what) {
  if (!std::isfinite(s) || s < 0 || s > 3600)
    raise(ErrorKind::invalid_argument, fmt::format("{} {} s is not allowed: 0..3600 s", what, s));
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s));
}

// The Python-side value types (plain data, built here).
struct PyJointState {
  double time = 0;  // s on the device's clock
  Array positions, device;
};

struct PyPose {
  Array position;     // m
  Array orientation;  // w, x, y, z
  double roll = 0, pitch = 0, yaw = 0;  // rad, as Arm::tool_rpy gives them
};

struct PyIkSolution {
  Array joints;
  std::optional<std::string> elbow;
  std::optional<bool> wrist_flipped, reaching_back;
};

struct PyJoint {
  std::string name, kind, role;
  double lower = 0, upper = 0, velocity = 0, acceleration = 0, jerk = 0;
  std::optional<int> robot_commands_id, joint_bus_id;
};

struct PyReport {
  double elapsed = 0, t_reached = 0, duration = 0, period = 0;
  bool completed = false, stopped = false;
  std::size_t points = 0, reads = 0;
  double largest_following_error = 0;
  std::optional<std::string> largest_following_joint;
  double held = 0;  // s a late host held the motion (docs/motion.md)
};

// What a board move (move_joints, move_to, gripper) was planned to be, as every app answers
// a move: how long it takes and where it ends.
struct PyPlannedMove {
  double duration = 0;  // s
  Array targets;        // every joint, SI, the model's order
  std::string note;     // why it takes longer than asked ("" if it does not)
};

// A LIN or CIRC segment of armctl.Arm.path, as Python writes it.
// armctl.Lin / armctl.Circ: the Arm API's Cartesian move.
using PySegment = arm::CartesianMove;

Eigen::Vector3d vec3(const std::vector<double>& v, const char* what) {
  if (v.size() != 3)
    raise(ErrorKind::invalid_argument, fmt::format("{} has {} values: give x, y, z in m", what, v.size()));
  for (double x : v)
    if (!std::isfinite(x)) raise(ErrorKind::invalid_argument, fmt::format("{} must be finite (x, y, z in m)", what));
  return {v[0], v[1], v[2]};
}

std::optional<motion::Elbow> elbow_of(const std::optional<std::string>& e) {
  if (!e) return std::nullopt;
  if (auto v = motion::parse_elbow(*e)) return v;
  raise(ErrorKind::invalid_argument, fmt::format("elbow '{}' is not allowed: 'left', 'right' (SCARA), 'up', 'down' (xArm)", *e));
}

class PyArm {
 public:
  PyArm(const std::string& arm, const std::string& device, const std::string& scene) {
    session::SessionOptions options;
    options.scene = scene;
    // The GIL released while the embedded simulators start and HID boards answer.
    session_ = must(released([&] { return session::open_arm_session(arm, device, options); }));
  }

  // The scene file every plan is checked against (docs/scene.md), or None.
  std::optional<std::string> scene() {
    const armctl::scene::Scene s = arm().scene();
    if (s.file.empty()) return std::nullopt;
    return s.file.string();
  }
  void set_scene(const std::optional<std::string>& file) {
    armctl::scene::Scene s;
    if (file && !file->empty()) s = must(armctl::scene::load_scene(*file));
    must(arm().set_scene(std::move(s)));
  }

  // The scene's fence and reduced mode (docs/scene.md "Fence and reduced mode"): whether
  // each is on, None where the scene sets none.
  std::optional<bool> fence() {
    const armctl::scene::Scene s = arm().scene();
    return s.fence ? std::optional<bool>(s.fence->on) : std::nullopt;
  }
  void set_fence(bool on) { must(arm().set_fence(on)); }
  std::optional<bool> reduced_mode() {
    const armctl::scene::Scene s = arm().scene();
    return s.reduced ? std::optional<bool>(s.reduced->on) : std::nullopt;
  }
  void set_reduced_mode(bool on) { must(arm().set_reduced_mode(on)); }

  // Stops what another thread runs on this arm (a wait ends, a streamed motion stops on its
  // path), waits for it, then ends the device.
  void close() {
    const auto turn = gate_.close();
    py::gil_scoped_release nogil;
    session_.reset();
  }

  arm::Arm& arm() {
    if (!session_) gate_.raise_closed();
    return *session_->arm;
  }
  const arm::ArmModel& model() { return arm().model(); }

  std::vector<PyJoint> joints() {
    std::vector<PyJoint> out;
    for (const auto& j : model().joints) {
      PyJoint p;
      p.name = j.name;
      p.kind = j.dimension == Dimension::angle ? "revolute" : "prismatic";
      p.role = j.role == arm::JointRole::chain ? "chain" : "gripper";
      p.lower = j.limits.lower;
      p.upper = j.limits.upper;
      p.velocity = j.limits.velocity;
      p.acceleration = j.limits.acceleration;
      p.jerk = j.limits.jerk;
      if (auto* m = j.map(arm::Protocol::robot_commands)) p.robot_commands_id = m->id;
      if (auto* m = j.map(arm::Protocol::joint_bus)) p.joint_bus_id = m->id;
      out.push_back(p);
    }
    return out;
  }

  std::vector<std::string> joint_names() {
    std::vector<std::string> out;
    for (const auto& j : model().joints) out.push_back(j.name);
    return out;
  }

  PyJointState state_of(const arm::JointState& s) {
    return {seconds(s.time.time_since_epoch()), to_array(s.positions), to_array(s.device)};
  }

  PyJointState read() {
    arm::Arm& a = arm();
    auto s = [&] {
      py::gil_scoped_release nogil;
      return a.read();
    }();
    return state_of(must(std::move(s)));
  }

  PyPose pose_of(const motion::Pose& p, const motion::JointVector& chain) {
    PyPose out;
    out.position = to_array(std::vector<double>{p.position.x(), p.position.y(), p.position.z()});
    const auto& q = p.orientation;
    out.orientation = to_array(std::vector<double>{q.w(), q.x(), q.y(), q.z()});
    const motion::Rpy r = arm().tool_rpy(p, chain);
    out.roll = r.roll;
    out.pitch = r.pitch;
    out.yaw = r.yaw;
    return out;
  }

  PyPose pose() {
    arm::Arm& a = arm();
    auto s = [&] {
      py::gil_scoped_release nogil;
      return a.read();
    }();
    const auto q = a.chain_of(must(std::move(s)).positions);
    return pose_of(a.forward(q), q);
  }

  // Chain joints (or every joint: the gripper is ignored), each finite and within its limits:
  // a pose past a limit is not one the arm can take. Named in SI, as Python gives them.
  motion::JointVector chain_from(const std::vector<double>& q) {
    const int chain = model().chain_joints();
    if (static_cast<int>(q.size()) != chain && static_cast<int>(q.size()) != model().joint_count())
      raise(ErrorKind::invalid_argument, fmt::format("{} joint values given: arm '{}' takes {} (the chain) or {} (every joint)",
                                                     q.size(), model().name, chain, model().joint_count()));
    for (int i = 0; i < chain; ++i) {
      const arm::JointModel& j = model().joints[std::size_t(i)];
      const double x = q[std::size_t(i)];
      if (!j.limits.contains(x, 1e-9)) {  // false for NaN too
        const char* unit = j.dimension == Dimension::angle ? "rad" : "m";
        raise(ErrorKind::invalid_argument, fmt::format("joint {}: {:g} {} is not allowed: {:.4f}..{:.4f} {}", j.name, x,
                                                       unit, j.limits.lower, j.limits.upper, unit));
      }
    }
    motion::JointVector v(chain);
    for (int i = 0; i < chain; ++i) v[i] = q[std::size_t(i)];
    return v;
  }

  PyPose forward(const std::vector<double>& q) {
    const auto chain = chain_from(q);
    return pose_of(arm().forward(chain), chain);
  }

  arm::CartesianGoal goal_of(const std::vector<double>& position, std::optional<double> roll,
                             std::optional<double> pitch, std::optional<double> yaw,
                             const std::optional<std::string>& elbow, bool nearest) {
    arm::CartesianGoal g;
    g.position = vec3(position, "position");
    g.roll = roll;
    g.pitch = pitch;
    g.yaw = yaw;
    g.elbow = elbow_of(elbow);
    g.nearest_orientation = nearest;
    return g;
  }

  std::vector<PyIkSolution> inverse(const std::vector<double>& position, std::optional<double> roll,
                                    std::optional<double> pitch, std::optional<double> yaw,
                                    const std::optional<std::string>& elbow, bool nearest,
                                    const std::optional<std::vector<double>>& near) {
    const arm::CartesianGoal g = goal_of(position, roll, pitch, yaw, elbow, nearest);
    arm::Arm& a = arm();
    arm::JointState now;
    if (near) {
      if (static_cast<int>(near->size()) != model().joint_count())
        raise(ErrorKind::invalid_argument,
              fmt::format("near has {} values: arm '{}' has {} joints", near->size(), model().name, model().joint_count()));
      now.positions = *near;
    } else {
      auto s = [&] {
        py::gil_scoped_release nogil;
        return a.read();
      }();
      now = must(std::move(s));
    }
    std::vector<PyIkSolution> out;
    for (const auto& s : must(a.inverse(g, now))) {
      PyIkSolution p;
      p.joints = to_array(Eigen::VectorXd(s.joints));
      if (s.configuration.elbow) p.elbow = motion::to_string(*s.configuration.elbow);
      p.wrist_flipped = s.configuration.wrist_flipped;
      p.reaching_back = s.configuration.reaching_back;
      out.push_back(p);
    }
    return out;
  }

  // A joint given as its name (any case) or its index in the model's order.
  int joint_index(const py::handle& key) {
    if (py::isinstance<py::str>(key)) {
      const auto name = key.cast<std::string>();
      if (auto i = model().find_joint(name)) return *i;
      raise(ErrorKind::invalid_argument,
            fmt::format("arm {} has no joint '{}'; joints: {}", model().name, name, fmt::join(joint_names(), ", ")));
    }
    if (py::isinstance<py::int_>(key)) {
      const long i = key.cast<long>();
      if (i >= 0 && i < model().joint_count()) return static_cast<int>(i);
      raise(ErrorKind::invalid_argument,
            fmt::format("joint index {} is not allowed: 0..{}", i, model().joint_count() - 1));
    }
    raise(ErrorKind::invalid_argument, "a joint is named by its name (str) or its index (int)");
  }

  // Targets as Python gives them: a sequence with one entry per joint (None: keep), or a
  // mapping {name or index: value}.
  std::vector<std::optional<double>> targets_of(const py::object& targets) {
    std::vector<std::optional<double>> out(std::size_t(model().joint_count()));
    auto value = [](const py::handle& v) -> std::optional<double> {
      if (v.is_none()) return std::nullopt;
      return v.cast<double>();
    };
    if (py::isinstance<py::dict>(targets)) {
      for (auto [k, v] : targets.cast<py::dict>()) out[std::size_t(joint_index(k))] = value(v);
      return out;
    }
    if (py::isinstance<py::str>(targets) || !py::isinstance<py::sequence>(targets))
      raise(ErrorKind::invalid_argument, "targets: a sequence with one value per joint (None keeps it) or a dict");
    const auto seq = py::reinterpret_borrow<py::sequence>(targets);
    if (seq.size() != out.size())
      raise(ErrorKind::invalid_argument, fmt::format("{} targets given: arm '{}' has {} joints ({}); use None to keep one",
                                                     seq.size(), model().name, out.size(), fmt::join(joint_names(), ", ")));
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = value(seq[i]);
    return out;
  }

  // A PTP as Python asks it: at `speed` of the velocity limits, or all joints arriving after
  // `duration` s (stretched to what the arm file allows: arm::joint_move_duration, the note
  // is a UserWarning).
  static arm::PtpMove ptp_move(std::optional<double> duration, double speed) {
    arm::PtpMove m;
    if (duration) m.duration = *duration;  // the planner refuses one outside 0..motion::kMaxMoveDuration
    m.duration_words = fmt::format("duration={:g}", duration.value_or(0));
    m.speed = speed;
    return m;
  }
  static void warn_note(const std::string& note) {
    if (!note.empty() && PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1) != 0) throw py::error_already_set();
  }

  static arm::WaitOptions wait_options(double timeout, std::optional<double> poll, double angle_tolerance,
                                       double length_tolerance) {
    arm::WaitOptions w;
    w.timeout = duration_of(timeout, "timeout");
    if (poll) w.poll = duration_of(*poll, "poll");
    if (!(angle_tolerance > 0) || !(length_tolerance > 0))
      raise(ErrorKind::invalid_argument, "tolerances must be above 0 (rad, m)");
    w.angle_tolerance = angle_tolerance;
    w.length_tolerance = length_tolerance;
    return w;
  }

  // Waits with the GIL released; Ctrl-C: Arm::stop, then KeyboardInterrupt; stop() or
  // close() from another thread: Arm::stop, then armctl.Error.
  PyJointState wait_with(arm::WaitOptions w) {
    arm::Arm& a = arm();
    InterruptWatch watch;
    bool closed = false, stopped = false;
    w.interrupted = [&] {
      closed = gate_.closing();
      stopped = gate_.stop_asked();
      return closed || stopped || watch.check();
    };
    auto s = [&] {
      py::gil_scoped_release nogil;
      auto r = a.wait(w);
      if (watch.tripped() || closed || stopped) (void)a.stop();
      return r;
    }();
    if (watch.tripped()) watch.rethrow();
    if (closed) gate_.raise_closed("a wait (the arm was stopped)");
    if (stopped) raise(ErrorKind::device, "the wait ended: stop() was called during it (the arm was stopped)");
    return state_of(must(std::move(s)));
  }

  PyJointState wait(double timeout, std::optional<double> poll, double angle_tolerance, double length_tolerance) {
    return wait_with(wait_options(timeout, poll, angle_tolerance, length_tolerance));
  }

  template <typename F>
  void command(F&& f) {
    arm::Arm& a = arm();
    auto s = [&] {
      py::gil_scoped_release nogil;
      return f(a);
    }();
    must(s);
  }

  // A board move (the device interpolates; arm::PtpRun::board) from where the arm stands,
  // then, with wait=True, until it arrives (as wait(timeout)). With `avoid`, a move whose
  // direct motion would collide goes around (arm/avoid_path.hpp): through waypoints, streamed.
  PyPlannedMove board_move(arm::PtpMove move, bool wait_for_it, double timeout,
                           const std::optional<arm::AvoidOptions>& avoid = std::nullopt) {
    const std::vector<double> from = here();
    arm::PlanOptions board;
    board.ptp = arm::PtpRun::board;
    if (avoid) move = must(arm::avoiding_move(*arm().kinematics(), from, move, *avoid, board)).move;
    auto plan = must(arm::plan_moves(*arm().kinematics(), from, std::vector<arm::Move>{{move}}, board));
    std::optional<arm::WaitOptions> wait;
    if (wait_for_it) wait = wait_options(timeout, std::nullopt, arm::kArrivalAngleTolerance, arm::kArrivalLengthTolerance);
    const Ran ran = run(plan, 1.0, wait, "a wait (the arm was stopped)");
    warn_note(plan.notes());
    if (ran.stop_called && ran.report.stopped)
      raise(ErrorKind::device, "the wait ended: stop() was called during it (the arm was stopped)");
    return {plan.duration, to_array(plan.end()), plan.notes()};
  }

  PyPlannedMove move_joints(const py::object& targets, std::optional<double> duration, double speed,
                            bool wait_for_it, double timeout) {
    arm::PtpMove m = ptp_move(duration, speed);
    m.target = targets_of(targets);
    return board_move(m, wait_for_it, timeout);
  }

  PyPlannedMove move_to(const std::vector<double>& position, std::optional<double> roll, std::optional<double> pitch,
               std::optional<double> yaw, const std::optional<std::string>& elbow, bool nearest,
               std::optional<double> duration, double speed, bool wait_for_it, double timeout, bool avoid,
               double avoid_time) {
    arm::PtpMove m = ptp_move(duration, speed);
    m.target = goal_of(position, roll, pitch, yaw, elbow, nearest);
    std::optional<arm::AvoidOptions> around;
    if (avoid) around = avoid_options(avoid_time);
    return board_move(m, wait_for_it, timeout, around);
  }

  // The search's budget for avoid=True (s), refused outside what the planner allows.
  static arm::AvoidOptions avoid_options(double avoid_time) {
    if (!(avoid_time >= arm::kMinAvoidTime && avoid_time <= arm::kMaxAvoidTime))
      raise(ErrorKind::invalid_argument, fmt::format("avoid_time {:g} s is outside {:g}..{:g} s", avoid_time,
                                                     arm::kMinAvoidTime, arm::kMaxAvoidTime));
    arm::AvoidOptions o;
    o.time_budget = avoid_time;
    return o;
  }

  PyPlannedMove gripper(double closed_fraction, std::optional<double> duration, double speed, bool wait_for_it,
               double timeout) {
    if (!model().gripper)
      raise(ErrorKind::unsupported, fmt::format("arm '{}' has no gripper", model().name));
    if (!std::isfinite(closed_fraction) || closed_fraction < 0 || closed_fraction > 1)
      raise(ErrorKind::invalid_argument,
            fmt::format("gripper: {} is outside 0..1 (0 = open, 1 = closed)", closed_fraction));
    arm::PtpMove m = ptp_move(duration, speed);
    std::vector<std::optional<double>> targets(std::size_t(model().joint_count()));
    targets[std::size_t(model().gripper->joint)] = model().gripper->at(closed_fraction);
    m.target = targets;
    return board_move(m, wait_for_it, timeout);
  }

  void stop() {
    command([](arm::Arm& a) { return a.stop(); });
  }
  // stop() as bound: the calls before it stop first (DeviceGate::stop), so that the stop does
  // not wait for its turn until their moves would have ended. From a signal handler during a
  // call on this thread, asking is all: that call stops the arm at its next check.
  void stop_now() {
    if (const auto turn = gate_.stop()) stop();
  }
  void set_torque(bool on) {
    command([on](arm::Arm& a) { return a.set_torque(on); });
  }

  // What `armctl arm health` prints (ArmDevice::health): the supply, and a line per fault.
  py::dict health() {
    arm::Arm& a = arm();
    const arm::DeviceHealth h = [&] {
      py::gil_scoped_release nogil;
      return a.device().health();
    }();
    py::dict out;
    out["battery_volts"] = h.battery_volts ? py::cast(*h.battery_volts) : py::none();
    out["faults"] = h.faults;
    return out;
  }

  void clear_faults() {
    command([](arm::Arm& a) { return a.device().clear_faults(); });
  }

  // Runs a plan (arm::run_motion) with the GIL released; `wait`: the wait for arrival at its
  // end (none: a board move returns once sent). Ctrl-C: the runner's stop (a streamed motion
  // decelerates on its path, a board move is halted), then KeyboardInterrupt; close() from
  // another thread: the same stop, then armctl.Error naming `during`; stop() from another
  // thread: the same stop, and the report says so (stopped, not completed).
  struct Ran {
    arm::RunReport report;
    bool stop_called = false;  // by stop() from another thread
  };
  Ran run(const arm::Plan& plan, double speed_override, const std::optional<arm::WaitOptions>& wait,
          const char* during) {
    must(check_fraction_in(speed_override, "speed_override", motion::kMinSpeedFraction, motion::kMaxSpeedFraction));
    arm::Arm& a = arm();
    InterruptWatch watch;
    bool closed = false, stopped = false;
    auto stop_asked = [&] {
      closed = closed || gate_.closing();
      stopped = stopped || gate_.stop_asked();
      return closed || stopped || watch.check();
    };
    arm::RunHooks hooks;
    hooks.speed_override = speed_override;
    hooks.command = [&] { return stop_asked() ? arm::MotionCommand::stop : arm::MotionCommand::none; };
    if (wait) hooks.wait = *wait;
    hooks.wait_for_arrival = wait.has_value();
    hooks.wait.interrupted = stop_asked;
    auto r = [&] {
      py::gil_scoped_release nogil;
      auto report = arm::run_motion(a, plan, hooks);
      if (watch.tripped() || closed) (void)a.stop();
      return report;
    }();
    if (watch.tripped()) watch.rethrow();
    if (closed) gate_.raise_closed(during);
    return {must(std::move(r)), stopped};
  }

  // Streams a planned motion (arm::run_motion, then the wait for arrival at its end).
  PyReport execute(const arm::Plan& plan, double speed_override) {
    const arm::RunReport m = run(plan, speed_override, arm::WaitOptions{}, "a streamed motion (the arm stopped on its path)").report;
    PyReport p;
    const arm::MotionReport last = m.last_motion.value_or(arm::MotionReport{});
    p.elapsed = seconds(m.elapsed);
    p.t_reached = m.t_reached;
    p.duration = plan.duration;
    p.period = seconds(last.period);
    p.completed = m.completed;
    p.stopped = m.stopped;
    p.points = last.points;
    p.reads = last.reads;
    p.largest_following_error = m.largest_following_error;
    p.held = seconds(last.held);
    if (m.largest_following_joint >= 0)
      p.largest_following_joint = model().joints[std::size_t(m.largest_following_joint)].name;
    return p;
  }

  std::vector<double> here() {
    arm::Arm& a = arm();
    auto s = [&] {
      py::gil_scoped_release nogil;
      return a.read();
    }();
    return must(std::move(s)).positions;
  }

  PyReport joint_move(const py::object& target, const std::vector<py::object>& waypoints, double speed,
                      double min_duration, double speed_override) {
    const std::vector<double> from = here();
    auto full = [&](const py::object& t) {
      const auto targets = targets_of(t);
      std::vector<double> q = from;
      for (std::size_t i = 0; i < q.size(); ++i)
        if (targets[i]) q[i] = *targets[i];
      return q;
    };
    arm::PtpMove move;
    for (const auto& w : waypoints) move.waypoints.push_back(full(w));
    const std::vector<double> to = full(target);
    move.target = std::vector<std::optional<double>>(to.begin(), to.end());
    move.speed = speed;
    move.min_duration = min_duration;
    return execute(must(arm::plan_moves(*arm().kinematics(), from, std::vector<arm::Move>{{move}})), speed_override);
  }

  PyReport path(const std::vector<PySegment>& segments, double speed_override, double acceleration,
                double angular_acceleration) {
    if (segments.empty()) raise(ErrorKind::invalid_argument, "path: give at least one segment (armctl.Lin, armctl.Circ)");
    const std::vector<double> from = here();
    std::vector<arm::Move> moves;
    for (const auto& s : segments) moves.push_back({s});
    arm::PlanOptions o;
    o.timing.acceleration = acceleration;
    o.timing.angular_acceleration = angular_acceleration;
    return execute(must(arm::plan_moves(*arm().kinematics(), from, moves, o)), speed_override);
  }

  PyReport move_linear(const std::vector<double>& position, std::optional<double> roll, std::optional<double> pitch,
                       std::optional<double> yaw, double speed, double angular_speed, double speed_override) {
    PySegment s;
    s.goal.position = vec3(position, "position");
    s.goal.roll = roll;
    s.goal.pitch = pitch;
    s.goal.yaw = yaw;
    s.speed = speed;
    s.angular_speed = angular_speed;
    return path({s}, speed_override, motion::kDefaultToolAcceleration, motion::kDefaultToolAngularAcceleration);
  }

  // ---- programs (docs/programs.md): the CLI's `program check` and `program run`
  // Needs the GIL (errors are raised); here() releases it for its read.
  program::ProgramPlan plan_program_file(const std::string& file, const std::string& points, bool avoid,
                                        double avoid_time) {
    program::PlanOptions o;
    if (avoid) o.avoid = avoid_options(avoid_time);
    const program::LoadedProgram l = must(program::load_program(file, points));
    const std::vector<double> from = here();
    return must(program::plan_program(*arm().kinematics(), from, l.flow, l.program.source, o));
  }

  py::dict check_program(const std::string& file, const std::string& points, bool avoid, double avoid_time) {
    const program::ProgramPlan p = plan_program_file(file, points, avoid, avoid_time);
    py::dict out;
    out["duration"] = p.duration;
    out["moves"] = p.moves;
    out["pieces"] = p.pieces.size();
    return out;
  }

  py::dict run_program(const std::string& file, const std::string& points, double speed_override, bool avoid,
                       double avoid_time) {
    must(check_fraction_in(speed_override, "speed_override", motion::kMinSpeedFraction, motion::kMaxSpeedFraction));
    const program::ProgramPlan plan = plan_program_file(file, points, avoid, avoid_time);  // every check first
    arm::Arm& a = arm();  // may raise: not where the GIL is released
    InterruptWatch watch;
    bool closed = false;
    auto stop_asked = [&] {
      closed = closed || gate_.closing();
      return closed || gate_.stop_asked() || watch.check();
    };
    std::vector<std::string> printed;
    auto r = [&] {
      py::gil_scoped_release nogil;
      program::RunOptions o;
      o.speed_override = speed_override;
      o.command = [&] { return stop_asked() ? arm::MotionCommand::stop : arm::MotionCommand::none; };
      o.wait.interrupted = stop_asked;  // the final wait, too
      o.on_event = [&](const program::RunEvent& e) {
        if (e.kind == program::RunEventKind::message && e.piece) printed.push_back(e.piece->text);
      };
      return program::run_plan(a, plan, o);
    }();
    if (watch.tripped()) watch.rethrow();
    if (closed) gate_.raise_closed("a program (the arm stopped on its path)");
    const program::RunReport& rep = must(std::move(r));
    py::dict out;
    out["completed"] = rep.completed;
    out["pieces"] = rep.pieces;
    out["elapsed"] = seconds(rep.elapsed);
    out["largest_following_error"] = rep.largest_following_error;
    out["printed"] = printed;
    return out;
  }

  // ---- action groups (Robot Commands devices only)
  arm::ActionGroups& groups() {
    arm::ActionGroups* groups = arm().device().action_groups();
    if (!groups)
      raise(ErrorKind::unsupported, fmt::format("action groups need a Robot Commands device; arm '{}' is on the joint bus "
                                                "(open it with a Robot Commands URI to go through the arm controller)",
                                                model().name));
    return *groups;
  }

  std::string description() { return arm().device().description(); }
  std::string protocol() { return arm::to_string(arm().device().protocol()); }

  DeviceGate gate_{"Arm"};  // before the session: it outlives it
  std::unique_ptr<session::ArmSession> session_;
};

// A bound call of PyArm: it takes its turn on the arm for its whole run (DeviceGate).
template <typename R, typename... A>
auto in_turn(R (PyArm::*call)(A...)) {
  return [call](PyArm& self, A... args) -> R {
    const auto turn = self.gate_.enter();
    return (self.*call)(std::forward<A>(args)...);
  };
}

PySegment segment(motion::SegmentKind kind, const std::vector<double>& position, const std::vector<double>& via,
                  std::optional<double> roll, std::optional<double> pitch, std::optional<double> yaw, double speed,
                  double angular_speed, double zone) {
  PySegment s;
  s.kind = kind;
  s.goal.position = vec3(position, "position");
  if (kind == motion::SegmentKind::circ) s.via = vec3(via, "via");
  s.goal.roll = roll;
  s.goal.pitch = pitch;
  s.goal.yaw = yaw;
  s.speed = speed;
  s.angular_speed = angular_speed;
  s.zone = zone;
  return s;
}

std::string repr_array(const Array& a) { return py::repr(a).cast<std::string>(); }

}  // namespace

void define_arm(py::module_& m) {
  // pybind11 (2.10) looks NumPy's C API up on first use, importing numpy inside a C++ static
  // initialisation; the import lets other threads run, and one whose first result is an array
  // then waits on that initialisation holding the GIL the import needs: a deadlock. Looked up
  // here, it happens once while `import armctl` runs, before any thread can call in.
  (void)Array(0);

  py::class_<PyJointState>(m, "JointState", "Every joint's position as read: SI and device units, and when.")
      .def_readonly("time", &PyJointState::time, "s on the device's clock, when the positions were read")
      .def_readonly("positions", &PyJointState::positions, "every joint, rad (revolute) or m (prismatic), the model's order")
      .def_readonly("device", &PyJointState::device, "the same in device units, as read (servo units, clicks)")
      .def("__repr__", [](const PyJointState& s) { return "JointState(positions=" + repr_array(s.positions) + ")"; });

  py::class_<PyPose>(m, "Pose", "A tool pose in the base frame.")
      .def_readonly("position", &PyPose::position, "x, y, z in m")
      .def_readonly("orientation", &PyPose::orientation, "unit quaternion w, x, y, z")
      .def_readonly("roll", &PyPose::roll, "rad, as people read them on this arm (Arm::tool_rpy)")
      .def_readonly("pitch", &PyPose::pitch, "rad")
      .def_readonly("yaw", &PyPose::yaw, "rad; on the xArm where the arm points")
      .def("__repr__", [](const PyPose& p) {
        return fmt::format("Pose(position={}, roll={:.4f}, pitch={:.4f}, yaw={:.4f})", repr_array(p.position), p.roll,
                           p.pitch, p.yaw);
      });

  py::class_<PyIkSolution>(m, "IkSolution", "One inverse-kinematics solution.")
      .def_readonly("joints", &PyIkSolution::joints, "chain joints, SI, base to tool")
      .def_readonly("elbow", &PyIkSolution::elbow, "'left'/'right' (SCARA), 'up'/'down' (xArm), or None")
      .def_readonly("wrist_flipped", &PyIkSolution::wrist_flipped, "SCARA: the wrist's second solution")
      .def_readonly("reaching_back", &PyIkSolution::reaching_back, "xArm: base turned half a turn, arm over the top")
      .def("__repr__", [](const PyIkSolution& s) { return "IkSolution(joints=" + repr_array(s.joints) + ")"; });

  py::class_<PyJoint>(m, "Joint", "One joint of the arm model (arm file + URDF).")
      .def_readonly("name", &PyJoint::name, "as in the arm file (find it in any case)")
      .def_readonly("kind", &PyJoint::kind, "'revolute' (rad) or 'prismatic' (m)")
      .def_readonly("role", &PyJoint::role, "'chain' or 'gripper'")
      .def_readonly("lower", &PyJoint::lower, "position limit, rad or m")
      .def_readonly("upper", &PyJoint::upper, "position limit, rad or m")
      .def_readonly("velocity", &PyJoint::velocity, "limit, per s")
      .def_readonly("acceleration", &PyJoint::acceleration, "limit, per s^2")
      .def_readonly("jerk", &PyJoint::jerk, "limit, per s^3")
      .def_readonly("robot_commands_id", &PyJoint::robot_commands_id, "servo ID on Robot Commands, or None")
      .def_readonly("joint_bus_id", &PyJoint::joint_bus_id, "joint number on the joint bus, or None")
      .def("__repr__", [](const PyJoint& j) {
        return fmt::format("Joint('{}', {}, {}..{})", j.name, j.kind, j.lower, j.upper);
      });

  py::class_<PyReport>(m, "MotionReport", "How a streamed motion (joint_move, move_linear, path) went.")
      .def_readonly("elapsed", &PyReport::elapsed, "s from the start, on the device's clock")
      .def_readonly("t_reached", &PyReport::t_reached, "nominal s of the plan where it ended")
      .def_readonly("duration", &PyReport::duration, "nominal s of the whole plan")
      .def_readonly("completed", &PyReport::completed, "reached the end of the motion")
      .def_readonly("stopped", &PyReport::stopped, "stopped on the path by stop() from another thread (Ctrl-C and close() raise instead)")
      .def_readonly("points", &PyReport::points, "stream points sent")
      .def_readonly("reads", &PyReport::reads, "position read-backs")
      .def_readonly("period", &PyReport::period, "s between stream points")
      .def_readonly("largest_following_error", &PyReport::largest_following_error, "SI, over all joints and reads")
      .def_readonly("largest_following_joint", &PyReport::largest_following_joint, "its joint, or None")
      .def_readonly("held", &PyReport::held, "s the motion was held for a late host (it ended that much later)")
      .def("__repr__", [](const PyReport& r) {
        return fmt::format("MotionReport(completed={}, elapsed={:.3f}, points={})", r.completed ? "True" : "False",
                           r.elapsed, r.points);
      });

  py::class_<PyPlannedMove>(m, "PlannedMove",
                            "What move_joints, move_to and gripper planned: as every armctl app answers a move.")
      .def_readonly("duration", &PyPlannedMove::duration, "s the move takes")
      .def_readonly("targets", &PyPlannedMove::targets, "every joint where it ends, SI, the model's order")
      .def_readonly("note", &PyPlannedMove::note, "why it takes longer than asked ('' if it does not)")
      .def("__repr__", [](const PyPlannedMove& p) {
        return fmt::format("PlannedMove(duration={:.3f}, targets={})", p.duration, repr_array(p.targets));
      });

  py::class_<PySegment>(m, "Segment", "A Cartesian path segment: made by armctl.Lin or armctl.Circ.")
      .def_property_readonly(
          "kind", [](const PySegment& s) { return std::string(motion::to_string(s.kind)); }, "'LIN' or 'CIRC'")
      .def_property_readonly(
          "position", [](const PySegment& s) { return to_array(Eigen::VectorXd(s.goal.position)); }, "its end point, m")
      .def_property_readonly(
          "via", [](const PySegment& s) { return to_array(Eigen::VectorXd(s.via)); }, "CIRC: a point on the arc, m")
      .def_property_readonly("roll", [](const PySegment& s) { return s.goal.roll; }, "rad at its end, or None: kept")
      .def_property_readonly("pitch", [](const PySegment& s) { return s.goal.pitch; }, "rad at its end, or None: kept")
      .def_property_readonly(
          "yaw", [](const PySegment& s) { return s.goal.yaw; }, "rad at its end, or None: kept (xArm: follows the position)")
      .def_readonly("speed", &PySegment::speed, "m/s of the tool point")
      .def_readonly("angular_speed", &PySegment::angular_speed, "rad/s of the tool orientation, at most")
      .def_readonly("zone", &PySegment::zone, "m: fly-by radius at its end; 0 = stop there");

  using namespace py::literals;
  m.def(
      "Lin",
      [](const std::vector<double>& position, std::optional<double> roll, std::optional<double> pitch,
         std::optional<double> yaw, double speed, double angular_speed, double zone) {
        return segment(motion::SegmentKind::lin, position, {}, roll, pitch, yaw, speed, angular_speed, zone);
      },
      "position"_a, "roll"_a = py::none(), "pitch"_a = py::none(), "yaw"_a = py::none(), "speed"_a = motion::kDefaultToolSpeed,
      "angular_speed"_a = motion::kDefaultToolAngularSpeed, "zone"_a = 0.0,
      "A straight line of the tool to `position` (x, y, z in m) at `speed` m/s (orientation turning at most\n"
      "`angular_speed` rad/s); roll, pitch, yaw (rad) left out keep the tool's; `zone` (m) blends the corner at\n"
      "its end (0: stop there).");
  m.def(
      "Circ",
      [](const std::vector<double>& via, const std::vector<double>& position, std::optional<double> roll,
         std::optional<double> pitch, std::optional<double> yaw, double speed, double angular_speed, double zone) {
        return segment(motion::SegmentKind::circ, position, via, roll, pitch, yaw, speed, angular_speed, zone);
      },
      "via"_a, "position"_a, "roll"_a = py::none(), "pitch"_a = py::none(), "yaw"_a = py::none(), "speed"_a = motion::kDefaultToolSpeed,
      "angular_speed"_a = motion::kDefaultToolAngularSpeed, "zone"_a = 0.0,
      "A circular arc of the tool through `via` to `position` (m); the rest as for Lin.");

  PyServo::define(m);
  py::class_<PyArm>(m, "Arm",
                    "One arm in SI units over any device (the C++ armctl::arm::Arm).\n\n"
                    "Arm(arm='xarm', device='') opens the shipped 'xarm' or 'scara' arm, or an arm file path, on\n"
                    "the device URI: '' = the embedded simulator (an emulated xArm board, or the simulated SCARA on\n"
                    "its joint bus), 'hid', 'serial:/dev/ttyUSB0', 'unix:/tmp/scara.sock', ... exactly as\n"
                    "`armctl arm --device`; scene: a scene file (docs/scene.md), as `--scene`. Joints in rad or m in the model's order; every value is checked\n"
                    "before anything moves (armctl.Error, kind 'invalid_argument'). Ctrl-C during a move or a wait\n"
                    "stops the arm, then raises KeyboardInterrupt. Threads may share an Arm: calls take turns on\n"
                    "the device. Use as a context manager to close it.")
      .def(py::init<const std::string&, const std::string&, const std::string&>(), "arm"_a = "xarm", "device"_a = "",
           "scene"_a = "")
      .def_property("scene", in_turn(&PyArm::scene), in_turn(&PyArm::set_scene),
                    "The scene file (docs/scene.md) every motion is checked against before it starts, or None (the arm's\n"
                    "own links only). Set a path to load one (a bad file raises armctl.Error and keeps the old one),\n"
                    "None to clear it.")
      .def_property("fence", in_turn(&PyArm::fence), in_turn(&PyArm::set_fence),
                    "Whether the scene's fence is on (True, False), or None when the scene sets none. Set True or False to\n"
                    "switch it (docs/scene.md \"Fence and reduced mode\"); setting it without a fence raises armctl.Error.")
      .def_property("reduced_mode", in_turn(&PyArm::reduced_mode), in_turn(&PyArm::set_reduced_mode),
                    "Whether the scene's reduced mode (tool speed cap, narrower joint ranges) is on, or None when the scene\n"
                    "sets none. Set True or False to switch it; setting it without one raises armctl.Error.")
      .def("close", &PyArm::close, "Closes the device (an embedded simulator ends). What another thread runs is stopped first (a wait\n"
           "ends, a streamed motion stops on its path; that call raises armctl.Error) and waited for. Later\n"
           "calls raise armctl.Error.")
      .def("__enter__", [](PyArm& a) -> PyArm& { return a; }, py::return_value_policy::reference)
      .def("__exit__", [](PyArm& a, py::object, py::object, py::object) { a.close(); })
      .def_property_readonly("name", [](PyArm& a) {
            const auto turn = a.gate_.enter();
            return a.model().name;
          }, "the arm model's name")
      .def_property_readonly("joints", in_turn(&PyArm::joints), "every joint: name, kind, role, limits, device ids")
      .def_property_readonly("joint_names", in_turn(&PyArm::joint_names), "the joints' names, in the model's order")
      .def_property_readonly("chain_joints", [](PyArm& a) {
                               const auto turn = a.gate_.enter();
                               return a.model().chain_joints();
                             },
                             "how many joints the kinematic chain has (the gripper follows them)")
      .def_property_readonly("protocol", in_turn(&PyArm::protocol), "'robot_commands' or 'joint_bus'")
      .def_property_readonly("device_description", in_turn(&PyArm::description), "what the arm is driven through")
      .def("read", in_turn(&PyArm::read), "Every joint's position now (JointState: SI and device units).")
      .def("pose", in_turn(&PyArm::pose), "The tool pose where the arm stands now.")
      .def("forward", in_turn(&PyArm::forward), "q"_a,
           "Forward kinematics (nothing sent): the tool pose at chain joints `q` (or every joint, gripper ignored).\n"
           "A value that is not finite or past its joint's limits raises armctl.Error naming the joint, the value\n"
           "and the range.")
      .def("inverse", in_turn(&PyArm::inverse), "position"_a, "roll"_a = py::none(), "pitch"_a = py::none(),
           "yaw"_a = py::none(), "elbow"_a = py::none(), "nearest_orientation"_a = false, "near"_a = py::none(),
           "Every IK solution for the tool at `position` (m), nearest to `near` (every joint; default: read()) first.\n"
           "roll, pitch, yaw (rad) left out keep the tool's (xArm: yaw follows the position); elbow keeps one\n"
           "configuration; nearest_orientation lets the 5-joint xArm reach the position with the nearest orientation.\n"
           "Unreachable: armctl.Error saying why (beyond reach by N mm, joint outside its limits). Nothing moves.")
      .def("move_joints", in_turn(&PyArm::move_joints), "targets"_a, "duration"_a = py::none(), "speed"_a = motion::kDefaultJointSpeed,
           "wait"_a = false, "timeout"_a = seconds(arm::kArrivalTimeout),
           "Moves the joints that have a target: a sequence with one value per joint (None keeps it) or a dict\n"
           "{name or index: value}, SI. All arrive together after `duration` s, or with the slowest at `speed` (0..1]\n"
           "of its velocity limit. wait=True: wait(timeout) afterwards.")
      .def("move_to", in_turn(&PyArm::move_to), "position"_a, "roll"_a = py::none(), "pitch"_a = py::none(),
           "yaw"_a = py::none(), "elbow"_a = py::none(), "nearest_orientation"_a = false, "duration"_a = py::none(),
           "speed"_a = motion::kDefaultJointSpeed, "wait"_a = false, "timeout"_a = seconds(arm::kArrivalTimeout),
           "avoid"_a = false, "avoid_time"_a = 1.0,
           "PTP: moves the tool to `position` (m) through the IK solution nearest the current joints (as move_joints).\n"
           "avoid=True: when the direct move would collide, around the obstacles through a collision-free path\n"
           "found within `avoid_time` s (docs/scene.md \"Around obstacles\"), streamed; else Error.")
      .def("move_linear", in_turn(&PyArm::move_linear), "position"_a, "roll"_a = py::none(), "pitch"_a = py::none(),
           "yaw"_a = py::none(), "speed"_a = motion::kDefaultToolSpeed, "angular_speed"_a = motion::kDefaultToolAngularSpeed, "speed_override"_a = 1.0,
           "LIN: the tool along a straight line to `position` (m) at `speed` m/s, planned and checked on the host and\n"
           "streamed; returns when it is there (MotionReport). Ctrl-C stops on the line, then KeyboardInterrupt.")
      .def("check_program", in_turn(&PyArm::check_program), "file"_a, "points"_a = "", "avoid"_a = false,
           "avoid_time"_a = 1.0,
           "Checks a robot program (docs/programs.md) before anything moves: every point resolves, every move is\n"
           "reachable and inside the joint limits along its whole path. Returns {'duration': s, 'moves', 'pieces'};\n"
           "armctl.Error names the file, line and why. `points`: the points file (default FILE.points if it exists).\n"
           "avoid=True: a PTP whose direct motion would collide goes around (as move_to's avoid), each search\n"
           "`avoid_time` s at most.")
      .def("run_program", in_turn(&PyArm::run_program), "file"_a, "points"_a = "", "speed_override"_a = 1.0,
           "avoid"_a = false, "avoid_time"_a = 1.0,
           "Checks, then runs a robot program on the arm. Returns {'completed', 'pieces', 'elapsed', \n"
           "'largest_following_error', 'printed'}. Ctrl-C stops on the path, then KeyboardInterrupt. avoid, avoid_time:\n"
           "as check_program's.")
      .def("path", in_turn(&PyArm::path), "segments"_a, "speed_override"_a = 1.0, "acceleration"_a = motion::kDefaultToolAcceleration,
           "angular_acceleration"_a = motion::kDefaultToolAngularAcceleration,
           "Runs a Cartesian path: a list of armctl.Lin / armctl.Circ, corners blended by their zones, timed with\n"
           "the tool's `acceleration` (m/s^2) and `angular_acceleration` (rad/s^2). The whole path is checked first.\n"
           "Ctrl-C stops on the path, then KeyboardInterrupt.")
      .def("joint_move", in_turn(&PyArm::joint_move), "target"_a, "waypoints"_a = std::vector<py::object>{}, "speed"_a = motion::kDefaultJointSpeed,
           "min_duration"_a = 0.0, "speed_override"_a = 1.0,
           "A jerk-limited joint move (plan_joint_move), streamed: through `waypoints` without stopping to `target`\n"
           "(each as for move_joints), at `speed` of the velocity limits, taking at least `min_duration` s.")
      .def("wait", in_turn(&PyArm::wait), "timeout"_a = seconds(arm::kArrivalTimeout), "poll"_a = py::none(), "angle_tolerance"_a = arm::kArrivalAngleTolerance,
           "length_tolerance"_a = arm::kArrivalLengthTolerance,
           "Until every joint of the last move is within tolerance (rad, m) of its target and at rest; returns the\n"
           "JointState. Not arrived in `timeout` s: armctl.Error (kind 'timeout') naming every late joint.")
      .def("stop", &PyArm::stop_now,
           "Stops every joint where it is and holds it. A wait another thread runs ends (armctl.Error), a\n"
           "streamed motion stops on its path (its MotionReport: stopped), before the stop is sent.")
      .def(
          "servo",
          [](PyArm& a, double speed, double timeout, double max_linear_speed, double max_angular_speed) {
            const auto turn = a.gate_.enter();  // the arm is open
            return std::make_unique<PyServo>(a.arm(), a.gate_,
                                             servo_options(speed, timeout, max_linear_speed, max_angular_speed));
          },
          "speed"_a = 1.0, "timeout"_a = 0.2, "max_linear_speed"_a = 0.25, "max_angular_speed"_a = 1.5,
          py::keep_alive<0, 1>(),
          "A servo session (armctl.Servo), for a with block: the arm follows twists, joint velocities and targets\n"
          "as they are sent, within every limit, slowing near the ends of the joints' ranges, singularities and the\n"
          "scene; commands not renewed within `timeout` s bring it to rest. `speed`: fraction of the joints' velocity\n"
          "limits; the twist's speeds are clipped to max_linear_speed (m/s) and max_angular_speed (rad/s).")
      .def(
          "calibration",
          [](PyArm& a, bool servo_offsets) {
            const auto turn = a.gate_.enter();
            return make_calibration(a.arm(), a.gate_, a.session_->board, servo_offsets);
          },
          "servo_offsets"_a = true, py::keep_alive<0, 1>(),
          "The guided calibration (armctl.Calibration), for a with block: each step as a method, nothing written\n"
          "until confirm(). servo_offsets (default): an xArm joint's zero goes to the servo's own offset when it\n"
          "fits -125..125 units, else to the arm file; False: every zero to the arm file (docs/calibration.md).")
      .def("set_torque", in_turn(&PyArm::set_torque), "on"_a, "off: the arm can be moved by hand; on: hold where it stands.")
      .def("health", in_turn(&PyArm::health),
           "The supply and the joints' faults, as `armctl arm health` and the dashboard show them:\n"
           "{'battery_volts': float or None, 'faults': [str]}.")
      .def("clear_faults", in_turn(&PyArm::clear_faults),
           "Clears the faults the joints hold (fix the cause first): each holds where it is and drives\n"
           "again. Error (device) names the joints that could not be cleared; nothing to clear on an xArm.")
      .def("gripper", in_turn(&PyArm::gripper), "closed_fraction"_a, "duration"_a = py::none(), "speed"_a = motion::kDefaultGripperSpeed,
           "wait"_a = false, "timeout"_a = seconds(arm::kArrivalTimeout), "The gripper: 0 = open, 1 = closed, anything between.")
      .def(
          "download_group",
          [](PyArm& a, int group, const std::string& text) {
            if (group < 0 || group > 254) raise(ErrorKind::invalid_argument, fmt::format("group {} is not allowed: 0..254", group));
            const auto file = must(files::parse_action_group(text, "<text>"));
            const auto turn = a.gate_.enter();
            auto& g = a.groups();
            must(released([&] { return g.download(static_cast<std::uint8_t>(group), file.actions); }));
          },
          "group"_a, "text"_a,
          "Downloads an action group written in armctl's group-file format (docs/action-groups.md) to `group`.")
      .def(
          "run_group",
          [](PyArm& a, int group, int times) {
            if (group < 0 || group > 254 || times < 0 || times > 65535)
              raise(ErrorKind::invalid_argument,
                    fmt::format("group {} times {} is not allowed: group 0..254, times 0..65535 (0: forever)", group, times));
            const auto turn = a.gate_.enter();
            auto& g = a.groups();
            must(released([&] { return g.run(static_cast<std::uint8_t>(group), static_cast<std::uint16_t>(times)); }));
          },
          "group"_a, "times"_a = 1, "Runs an action group stored on the board `times` times (0: until stop_group).")
      .def(
          "stop_group",
          [](PyArm& a) {
            const auto turn = a.gate_.enter();
            auto& g = a.groups();
            must(released([&] { return g.stop(); }));
          },
          "Stops the running action group.")
      .def(
          "erase_group",
          [](PyArm& a, int group) {
            if (group < 0 || group > 255) raise(ErrorKind::invalid_argument, fmt::format("group {} is not allowed: 0..255 (255: all)", group));
            const auto turn = a.gate_.enter();
            auto& g = a.groups();
            must(released([&] { return g.erase(static_cast<std::uint8_t>(group)); }));
          },
          "group"_a, "Erases an action group (255: all of them).")
      .def(
          "group_events",
          [](PyArm& a, double timeout) {
            return group_events(a.gate_, [&]() -> arm::ActionGroups& { return a.groups(); }, timeout);
          }, "timeout"_a = 0.0,
          "The action-group notifications received so far (and within `timeout` s): a list of dicts\n"
          "{'kind': 'started'|'stopped'|'finished', 'group': int|None, 'count': int|None}.");
}

}  // namespace armctl::python

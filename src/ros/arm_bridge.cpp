#include "ros/arm_bridge.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "arm/plan_moves.hpp"
#include "arm/run_motion.hpp"
#include "motion/kinematics.hpp"
#include "ros/motion_lane.hpp"
#include "ros/trajectory_goal.hpp"
#include "ros/trajectory_job.hpp"
#include "scene/scene.hpp"
#include "session/arm_session.hpp"
#include "session/arm_worker.hpp"
#include "session/servo_lane.hpp"

namespace armctl::ros_node {

namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) throw ArmctlError(ErrorKind::io, fmt::format("cannot read {}", p.string()));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

ArmInfo info_of(const session::ArmSession& session) {
  const arm::ArmModel& model = session.arm->model();
  ArmInfo info;
  info.name = model.name;
  for (const auto& j : model.joints) info.joints.push_back(j.name);
  // The frames are the arm file's base_link and tool_link (docs/arm-files.md).
  const auto j = nlohmann::json::parse(read_text(model.file), nullptr, false);
  if (j.is_discarded() || !j.contains("base_link") || !j.contains("tool_link") || !j["base_link"].is_string() ||
      !j["tool_link"].is_string())
    throw ArmctlError(ErrorKind::invalid_config,
                      fmt::format("{}: base_link and tool_link (strings) are needed", model.file.string()));
  info.base_frame = j["base_link"].get<std::string>();
  info.tool_frame = j["tool_link"].get<std::string>();
  info.urdf = model.urdf_text;  // with the arm file's calibrated link lengths
  info.action_groups = session.arm->device().action_groups() != nullptr;
  return info;
}

ArmState state_of(const session::ArmSnapshot& s) {
  ArmState out;
  out.sequence = s.sequence;
  out.read_time = std::chrono::duration<double>(s.time.time_since_epoch()).count();
  out.link_ok = s.link_ok;
  out.link_error = s.link_error;
  out.positions = s.positions;
  out.velocities = s.velocities;
  out.battery_volts = s.status.battery_volts;
  out.faults = s.status.faults;
  out.job = s.job;
  out.last_error = s.last_error;
  if (s.progress) out.progress_t = s.progress->t;
  return out;
}

// A job the lane's stop dropped before it ran (a newer motion replaced it, or stop()).
bool is_stopped(const Status& s) {
  const auto* refused = s ? nullptr : session::job_refusal(s.error());
  return refused && refused->reason == session::JobRefused::Reason::dropped;
}

// A PTP sent as one board move from where the arm stands, then waited for (the one planner
// and runner: arm::plan_moves, arm::run_motion). A stop meanwhile halts the arm and ends
// the job with an error that says so.
// What a board move was planned to be: its duration and where it ends (every joint, SI).
struct PlannedMove {
  double duration = 0;
  std::vector<double> targets;
};

Status board_move(arm::Arm& a, session::JobContext& ctx, const arm::PtpMove& move, PlannedMove* planned = nullptr) {
  auto here = a.read();
  if (!here) return here.error();
  arm::PlanOptions o;
  o.ptp = arm::PtpRun::board;
  auto plan = arm::plan_moves(*a.kinematics(), here->positions, std::vector<arm::Move>{{move}}, o);
  if (!plan) return plan.error();
  if (planned) *planned = {plan->duration, plan->end()};
  arm::RunHooks hooks;
  hooks.command = [&ctx] { return ctx.stopping() ? arm::MotionCommand::stop : arm::MotionCommand::none; };
  hooks.wait = ctx.wait_options();
  auto report = arm::run_motion(a, *plan, hooks);
  if (!report) return report.error();
  if (report->stopped) return Error{ErrorKind::device, "stopped before the arm arrived"};
  return Ok{};
}

MotionOutcome refusal_outcome(const Error& e) {
  const GoalRefusal r = refusal_of(e);
  MotionOutcome m;
  m.code = r.code;
  m.kind = to_string(e.kind);
  m.message = r.message;
  return m;
}

}  // namespace

struct ArmBridge::Impl {
  BridgeOptions options;
  ArmInfo info;
  session::ArmWorker worker;
  MotionLane lane{worker};
  session::ServoLane servo{worker};

  Impl(const BridgeOptions& o, std::unique_ptr<session::ArmSession> session)
      : options(o), info(info_of(*session)), worker(std::move(session), worker_options(o)) {}

  static session::ArmWorkerOptions worker_options(const BridgeOptions& o) {
    session::ArmWorkerOptions w;
    if (o.poll) w.poll = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(*o.poll));
    return w;
  }

  const arm::ArmModel& model() const { return worker.model(); }

  Result<std::vector<double>> here() const {
    const auto s = worker.snapshot();
    if (!s.link_ok || s.positions.empty())
      return Error{ErrorKind::device, fmt::format("the arm's positions are not known: {}",
                                                  s.link_error.empty() ? "nothing read yet" : s.link_error),
                   GoalError::invalid_goal};
    return s.positions;
  }

  MotionOutcome run(const std::string& what, session::ArmWorker::Job job) {
    const Status s = lane.replace(what, std::move(job)).get();
    MotionOutcome m;
    m.ok = s.ok();
    m.stopped = is_stopped(s);
    if (!s) {
      m.kind = to_string(s.error().kind);
      m.message = s.error().message;
    }
    return m;
  }
};

namespace {

// ROS clients watch the arm live: the embedded simulated joint bus in step with the wall clock.
std::unique_ptr<session::ArmSession> open_session(const BridgeOptions& o) {
  session::SessionOptions so;
  so.wall_clock = true;
  so.scene = o.scene;
  so.fence = o.fence;
  so.reduced_mode = o.reduced_mode;
  return session::open_arm_session(o.arm, o.device, so).value();  // the bridge's constructor throws it
}

}  // namespace

ArmBridge::ArmBridge(const BridgeOptions& options) : impl_(std::make_unique<Impl>(options, open_session(options))) {}

ArmBridge::~ArmBridge() = default;

const ArmInfo& ArmBridge::info() const { return impl_->info; }

ArmState ArmBridge::state() const { return state_of(impl_->worker.snapshot()); }

ArmState ArmBridge::wait_for_update(std::uint64_t after, std::chrono::milliseconds timeout) const {
  return state_of(impl_->worker.wait_for_update(after, timeout));
}

std::optional<GoalRefusal> ArmBridge::check(const TrajectoryGoal& goal, double* duration) const {
  const auto& model = impl_->model();
  auto tolerances = map_tolerances(model, goal.request.joint_names, goal.path_tolerance, goal.goal_tolerance,
                                   goal.goal_time_tolerance);
  if (!tolerances) return refusal_of(tolerances.error());
  auto from = impl_->here();
  if (!from) return refusal_of(from.error());
  auto plan = plan_trajectory(*impl_->worker.kinematics(), *from, goal.request);
  if (!plan) return refusal_of(plan.error());
  if (duration) *duration = plan->motion.duration;
  return std::nullopt;
}

MotionOutcome ArmBridge::follow(const TrajectoryGoal& goal,
                                const std::function<void(const Desired&, const ArmState&)>& on_progress) {
  const auto& model = impl_->model();
  auto tolerances = map_tolerances(model, goal.request.joint_names, goal.path_tolerance, goal.goal_tolerance,
                                   goal.goal_time_tolerance);
  if (!tolerances) return refusal_outcome(tolerances.error());
  auto outcome = std::make_shared<TrajectoryOutcome>();
  TrajectoryDefaults defaults;
  defaults.goal_time = impl_->options.goal_time;
  const TrajectoryRequest request = goal.request;
  const GoalTolerances t = *tolerances;
  auto done = impl_->lane.replace("trajectory", [=](arm::Arm& a, session::JobContext& ctx) {
    return run_trajectory(a, ctx, request, t, defaults, *outcome);
  });
  // Feedback at every read-back: the plan where the arm should have been at that read.
  std::uint64_t seen = 0, reads = 0;
  while (done.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    const auto s = impl_->worker.wait_for_update(seen, std::chrono::milliseconds(100));
    seen = s.sequence;
    if (!on_progress) continue;
    Desired d;
    ArmState now = state_of(s);
    {
      std::lock_guard<std::mutex> lock(outcome->mutex);
      if (!outcome->plan || outcome->last_read.count == reads) continue;
      reads = outcome->last_read.count;
      d.t = outcome->last_read.t;
      now.positions = outcome->last_read.positions;
      now.velocities = outcome->last_read.velocities;
      std::vector<double> a;
      outcome->plan->motion.sample(d.t, d.positions, d.velocities, a);
    }
    on_progress(d, now);
  }
  const Status status = done.get();
  MotionOutcome m;
  std::lock_guard<std::mutex> lock(outcome->mutex);
  if (outcome->stopped || (is_stopped(status) && outcome->code == GoalError::none)) {
    m.stopped = true;
    m.message = "stopped before the end (canceled, replaced or stopped): the arm came to rest on the path";
  } else if (!status) {
    m.code = outcome->code == GoalError::none ? GoalError::invalid_goal : outcome->code;
    m.message = status.error().message;
  } else {
    m.ok = true;
    m.message = "arrived within the goal tolerance";
  }
  return m;
}

MotionOutcome ArmBridge::move_to(const std::vector<double>& position, const std::vector<double>& quaternion) {
  if (position.size() != 3 || quaternion.size() != 4)
    return refusal_outcome(Error{ErrorKind::invalid_argument, "a pose is x, y, z (m) and w, x, y, z (unit quaternion)"});
  double norm = 0;
  for (double q : quaternion) norm += q * q;
  norm = std::sqrt(norm);
  bool finite = std::isfinite(norm);
  for (double p : position) finite = finite && std::isfinite(p);
  if (!finite || std::abs(norm - 1) > 1e-3)
    return refusal_outcome(Error{ErrorKind::invalid_argument,
                                 fmt::format("the position must be finite and the orientation a unit quaternion (its "
                                             "norm is {})", norm)});
  arm::CartesianGoal goal;
  goal.position = {position[0], position[1], position[2]};
  const motion::Rpy r =
      motion::to_rpy(Eigen::Quaterniond(quaternion[0], quaternion[1], quaternion[2], quaternion[3]));
  goal.roll = r.roll;
  goal.pitch = r.pitch;
  goal.yaw = r.yaw;
  goal.nearest_orientation = true;  // the 5-joint xArm: the nearest orientation it can reach
  arm::PtpMove move;
  move.target = goal;
  move.speed = impl_->options.move_speed;
  auto planned = std::make_shared<PlannedMove>();  // written by the job, read once it ended
  MotionOutcome o = impl_->run("pose goal", [move, planned](arm::Arm& a, session::JobContext& ctx) -> Status {
    return board_move(a, ctx, move, planned.get());
  });
  o.duration = planned->duration;
  o.targets = planned->targets;
  return o;
}

MotionOutcome ArmBridge::set_torque(bool on) {
  return impl_->run(on ? "torque on" : "torque off",
                    [on](arm::Arm& a, session::JobContext&) { return a.set_torque(on); });
}

MotionOutcome ArmBridge::clear_faults() {
  return impl_->run("clear faults", session::clear_faults);  // /diagnostics says so at once
}

MotionOutcome ArmBridge::gripper(double closed_fraction) {
  if (!std::isfinite(closed_fraction) || closed_fraction < 0 || closed_fraction > 1)
    return refusal_outcome(Error{ErrorKind::invalid_argument,
                                 fmt::format("closed_fraction {} is not allowed: 0 (open) to 1 (closed)", closed_fraction)});
  // The gripper's own default, as in every app (the `speed` parameter is for pose goals).
  const double speed = motion::kDefaultGripperSpeed;
  return impl_->run("gripper", [closed_fraction, speed](arm::Arm& a, session::JobContext& ctx) -> Status {
    const arm::ArmModel& model = a.model();
    if (!model.gripper) return Error{ErrorKind::unsupported, fmt::format("arm '{}' has no gripper", model.name)};
    std::vector<std::optional<double>> targets(std::size_t(model.joint_count()));
    targets[std::size_t(model.gripper->joint)] = model.gripper->at(closed_fraction);
    arm::PtpMove move;
    move.target = targets;
    move.speed = speed;
    return board_move(a, ctx, move);
  });
}

namespace {

MotionOutcome scene_edit_outcome(const Status& s) {
  if (!s) {
    MotionOutcome m;
    m.kind = to_string(s.error().kind);
    m.message = s.error().message;
    return m;
  }
  MotionOutcome m;
  m.ok = true;
  return m;
}

}  // namespace

MotionOutcome ArmBridge::set_scene_object(const std::string& object) {
  return scene_edit_outcome(impl_->worker.session().arm->edit_scene(
      [&](const scene::Scene& now) { return scene::with_object(now, object, "object"); }));
}

MotionOutcome ArmBridge::remove_scene_object(const std::string& name) {
  return scene_edit_outcome(impl_->worker.session().arm->edit_scene(
      [&](const scene::Scene& now) { return scene::without_object(now, name); }));
}

MotionOutcome ArmBridge::set_fence(bool on) {
  return scene_edit_outcome(impl_->worker.session().arm->set_fence(on));
}

MotionOutcome ArmBridge::set_reduced_mode(bool on) {
  return scene_edit_outcome(impl_->worker.session().arm->set_reduced_mode(on));
}

ArmBridge::Limits ArmBridge::limits() const {
  const scene::Scene s = impl_->worker.session().arm->scene();
  Limits out;
  if (s.fence) out.fence = s.fence->on;
  if (s.reduced) out.reduced_mode = s.reduced->on;
  return out;
}

MotionOutcome ArmBridge::run_action_group(int group, int times) {
  if (group < 0 || group > 254 || times < 0 || times > 65535)
    return refusal_outcome(Error{ErrorKind::invalid_argument,
                                 fmt::format("group {} times {} is not allowed: group 0..254, times 0..65535 (0: until "
                                             "stopped)", group, times)});
  if (!impl_->info.action_groups)
    return refusal_outcome(Error{ErrorKind::unsupported,
                                 "action groups run on a Robot Commands board (the xArm, or the SCARA through the arm "
                                 "controller); this arm is on the joint bus"});
  return impl_->run("action group", [group, times](arm::Arm& arm, session::JobContext&) {
    return arm.device().action_groups()->run(std::uint8_t(group), std::uint16_t(times));
  });
}

MotionOutcome ArmBridge::stop_action_group() {
  if (!impl_->info.action_groups)
    return refusal_outcome(Error{ErrorKind::unsupported,
                                 "action groups run on a Robot Commands board; this arm is on the joint bus"});
  return impl_->run("stop action group",
                    [](arm::Arm& arm, session::JobContext&) { return arm.device().action_groups()->stop(); });
}

void ArmBridge::stop() { impl_->lane.stop(); }

namespace {

std::string why_not(const Status& s) { return s ? std::string() : s.error().message; }

}  // namespace

std::string ArmBridge::servo_twist(const std::vector<double>& linear, const std::vector<double>& angular,
                                   bool tool_frame) {
  if (linear.size() != 3 || angular.size() != 3) return "a twist has three linear and three angular components";
  arm::ToolTwist t{Eigen::Vector3d(linear[0], linear[1], linear[2]), Eigen::Vector3d(angular[0], angular[1], angular[2]),
                   tool_frame ? arm::ServoFrame::tool : arm::ServoFrame::base};
  return why_not(impl_->servo.send(arm::ServoCommand{t, std::nullopt}));
}

std::string ArmBridge::servo_joints(const std::vector<std::string>& names, const std::vector<double>& velocities) {
  const arm::ArmModel& model = impl_->model();
  if (names.size() != velocities.size())
    return fmt::format("{} joint names and {} velocities: one velocity per name", names.size(), velocities.size());
  std::vector<double> v(std::size_t(model.joint_count()), 0.0);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto i = model.find_joint(names[k]);
    if (!i) return fmt::format("arm '{}' has no joint '{}'", model.name, names[k]);
    v[std::size_t(*i)] = velocities[k];
  }
  return why_not(impl_->servo.send(arm::ServoCommand{arm::JointVelocities{std::move(v)}, std::nullopt}));
}

}  // namespace armctl::ros_node

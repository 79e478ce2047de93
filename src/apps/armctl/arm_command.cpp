// armctl arm [--arm xarm|scara|FILE] [--device URI] [--json] COMMAND ...
// The Arm API from the command line: joints and tool pose in SI units (shown in deg and mm),
// joint and Cartesian moves, IK, torque, gripper, zero calibration.
#include <charconv>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "apps/armctl/clearance_words.hpp"
#include "apps/armctl/scene_option.hpp"
#include "apps/armctl/arm_motion.hpp"
#include "session/arm_session.hpp"
#include "apps/armctl/commands.hpp"
#include "apps/armctl/arm_json.hpp"
#include "apps/armctl/json_output.hpp"
#include "apps/armctl/motion_trace.hpp"
#include "apps/armctl/number_options.hpp"
#include "apps/armctl/serve_support.hpp"
#include "arm/arm_calibration.hpp"
#include "calibration/arm_file_writer.hpp"
#include "calibration/calibration_changes.hpp"
#include "arm/avoid_path.hpp"
#include "arm/plan_moves.hpp"
#include "arm/run_motion.hpp"
#include "core/error.hpp"
#include "core/must.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"
#include "scene/scene.hpp"

namespace armctl::cli {

namespace {

using nlohmann::json;

struct ArmArgs {
  SceneArgs scene;  // --scene FILE, --fence, --reduced-mode
  std::string arm = "xarm";
  std::string device;
  bool json = false;
  std::vector<std::string> words;  // NAME=VALUE or JOINT
  std::string time;
  std::string speed;
  bool wait = false;
  double timeout_s = 20;
  std::string elbow;
  bool nearest = false;
  std::string onoff;
  std::string gripper;
  bool linear = false;
  std::string zone;
  std::string speed_override;
  std::string path_file;
  std::string trace;  // path --trace FILE
  bool avoid = false;       // move-to --avoid
  std::string avoid_time;   // --avoid-time
};

[[noreturn]] void usage(const std::string& message) { throw ArmctlError(ErrorKind::invalid_argument, message); }


// The joint's map on the first protocol that drives it, in the protocols' order (a Robot
// Commands servo before a joint-bus joint, as the arm files list them).
const arm::DeviceMap* first_map(const arm::JointModel& j) {
  for (arm::Protocol p : arm::protocols())
    if (const arm::DeviceMap* map = j.map(p)) return map;
  return nullptr;
}

// A joint as the user names it: its name (any case) or its number — the servo ID on a
// Robot Commands arm, the joint number on the joint bus (the same numbers the devices use).
int find_joint(const arm::ArmModel& m, const std::string& word) {
  if (auto i = m.find_joint(word)) return *i;
  int n = 0;
  auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), n);
  if (ec == std::errc() && end == word.data() + word.size()) {
    for (int i = 0; i < m.joint_count(); ++i) {
      const arm::DeviceMap* map = first_map(m.joints[std::size_t(i)]);
      if (map && map->id == n) return i;
    }
  }
  std::string names;
  for (const auto& j : m.joints) names += fmt::format("{}{} ({})", names.empty() ? "" : ", ", j.name, first_map(j)->id);
  usage(fmt::format("arm {} has no joint '{}'; joints (and numbers): {}", m.name, word, names));
}

std::pair<std::string, std::string> split_assignment(const std::string& word, const char* form) {
  const auto eq = word.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == word.size())
    usage(fmt::format("'{}' is not {}", word, form));
  return {word.substr(0, eq), word.substr(eq + 1)};
}

// A PTP as the command line asks it: --time (the one duration rule: stretched to what the
// arm file allows, with a note) or --speed.
arm::PtpMove ptp_move(const ArmArgs& a) {
  arm::PtpMove m;
  if (!a.time.empty() && !a.speed.empty()) usage("--time and --speed cannot be used together");
  if (!a.time.empty()) {
    const double seconds = seconds_option(a.time, "--time");
    if (seconds > motion::kMaxMoveDuration)
      usage(fmt::format("--time '{}' is longer than {:g} s", a.time, motion::kMaxMoveDuration));
    m.duration = seconds;
    m.duration_words = "--time " + a.time;
  }
  if (!a.speed.empty()) m.speed = percent_option(a.speed, "--speed (of the joints' velocity limits)", 0);
  return m;
}

arm::WaitOptions wait_options(const ArmArgs& a) {
  arm::WaitOptions w;
  w.timeout = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(a.timeout_s));
  return w;
}

json joints_json(const arm::ArmModel& m, const arm::JointState& s) {
  json out = joint_values_json(m, s.positions);
  for (std::size_t i = 0; i < out.size(); ++i) out[i]["device"] = s.device[i];
  return out;
}

void print_joints(const ArmArgs& a, const arm::ArmModel& m, const arm::JointState& s) {
  if (a.json) {
    print_json_line(json{{"joints", joints_json(m, s)}});
    return;
  }
  for (int i = 0; i < m.joint_count(); ++i) {
    const auto& j = m.joints[std::size_t(i)];
    fmt::print("{:<10} {:>10.3f} {:<3}  (device {:.0f}){}\n", j.name, to_display(j.dimension, s.positions[std::size_t(i)]),
               display_unit(j.dimension), s.device[std::size_t(i)], j.role == arm::JointRole::gripper ? "  gripper" : "");
  }
}

// Degrees for people, without "-0.00".
double deg(double rad) { return to_display(Dimension::angle, rad); }

json pose_json(const motion::Pose& p, const motion::Rpy& r) {
  return {{"x_mm", p.position.x() * 1e3}, {"y_mm", p.position.y() * 1e3}, {"z_mm", p.position.z() * 1e3},
          {"roll_deg", deg(r.roll)}, {"pitch_deg", deg(r.pitch)}, {"yaw_deg", deg(r.yaw)}};
}

std::string pose_text(const motion::Pose& p, const motion::Rpy& r) {
  auto mm = [](double m) { return to_display(Dimension::length, m); };
  return fmt::format("x {:.2f} y {:.2f} z {:.2f} mm  roll {:.2f} pitch {:.2f} yaw {:.2f} deg", mm(p.position.x()),
                     mm(p.position.y()), mm(p.position.z()), deg(r.roll), deg(r.pitch), deg(r.yaw));
}

arm::CartesianGoal parse_goal(const ArmArgs& a) {
  arm::CartesianGoal g;
  std::optional<double> xyz[3];
  for (const auto& w : a.words) {
    auto [key, value] = split_assignment(w, "KEY=VALUE (x, y, z with mm or m; roll, pitch, yaw with deg or rad)");
    const int axis = key == "x" ? 0 : key == "y" ? 1 : key == "z" ? 2 : -1;
    if (axis >= 0) {
      if (xyz[axis]) usage(fmt::format("{} is given twice", key));
      xyz[axis] = must(parse_quantity(value, Dimension::length, key, 0, "mm"));
    } else if (key == "roll" || key == "pitch" || key == "yaw") {
      auto& slot = key == "roll" ? g.roll : key == "pitch" ? g.pitch : g.yaw;
      if (slot) usage(fmt::format("{} is given twice", key));
      slot = must(parse_quantity(value, Dimension::angle, key, 0, "deg"));
    } else {
      usage(fmt::format("'{}' is not a pose key: allowed x, y, z, roll, pitch, yaw", key));
    }
  }
  for (int k = 0; k < 3; ++k)
    if (!xyz[k]) usage(fmt::format("the tool position needs x, y and z ({} is missing)", "xyz"[k]));
  g.position = {*xyz[0], *xyz[1], *xyz[2]};
  if (!a.elbow.empty()) {
    g.elbow = motion::parse_elbow(a.elbow);
    if (!g.elbow) usage(fmt::format("--elbow '{}' is not allowed: left or right (scara), up or down (xarm)", a.elbow));
  }
  g.nearest_orientation = a.nearest;
  return g;
}

// Where the arm stands after a move (the read that found it arrived), and how far the tool
// is from `goal`.
void print_arrived(const ArmArgs& a, session::ArmSession& s, const std::optional<arm::CartesianGoal>& goal,
                   arm::JointState state) {
  const motion::JointVector q = s.arm->chain_of(state.positions);
  const motion::Pose pose = s.arm->forward(q);
  const motion::Rpy rpy = s.arm->tool_rpy(pose, q);
  if (a.json) {
    json out{{"joints", joints_json(s.arm->model(), state)}, {"pose", pose_json(pose, rpy)}};
    if (goal) out["position_error_mm"] = (pose.position - goal->position).norm() * 1e3;
    print_json_line(out);
    return;
  }
  print_joints(a, s.arm->model(), state);
  fmt::print("tool: {}\n", pose_text(pose, rpy));
  if (goal) fmt::print("position error: {:.2f} mm\n", (pose.position - goal->position).norm() * 1e3);
}

// move-to --avoid-time: how long the search around obstacles may take (default 1 s).
arm::AvoidOptions avoid_options(const ArmArgs& a) {
  arm::AvoidOptions o;
  o.time_budget = avoid_time_option(a.avoid_time, o.time_budget);
  return o;
}

// A PTP as one board move (the device interpolates), planned and run by the one planner and
// runner (arm::plan_moves, arm::run_motion); with --wait, until the arm arrives. Ctrl-C
// while waiting halts the arm (the board would otherwise finish the move alone). With
// --avoid, a move whose direct motion would collide goes around (arm/avoid_path.hpp): through
// waypoints, host-planned and streamed.
void run_board_move(const ArmArgs& a, session::ArmSession& s, arm::PtpMove move,
                    const std::optional<arm::CartesianGoal>& goal) {
  const arm::JointState here = must(s.arm->read());
  arm::PlanOptions o;
  o.ptp = arm::PtpRun::board;
  std::optional<arm::AvoidingMove> avoided;
  if (a.avoid) {
    avoided = must(arm::avoiding_move(*s.arm->kinematics(), here.positions, move, avoid_options(a), o));
    move = avoided->move;
  }
  const arm::Plan plan = must(arm::plan_moves(*s.arm->kinematics(), here.positions, std::vector<arm::Move>{{move}}, o));
  if (const std::string note = plan.notes(); !note.empty()) fmt::print(stderr, "note: {}\n", note);
  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);  // before the plan is said: a Ctrl-C after it stops the move
  if (a.json) {  // what every app answers for a move: how long it takes and where it ends
    json planned{{"duration_s", plan.duration}, {"targets", joint_values_json(s.arm->model(), plan.end())}};
    add_clearance_json(planned, plan.clearance);
    if (avoided) planned["avoided"] = json{{"waypoints", avoided->waypoints}, {"planning_s", avoided->planning_s}};
    print_json_event("planned", std::move(planned));
  } else {
    if (avoided)
      fmt::print("{}\n", avoided->avoided ? fmt::format("around obstacles: {} waypoints, planned in {:.0f} ms", avoided->waypoints,
                                                        avoided->planning_s * 1e3)
                                          : std::string("the direct move is clear: no detour"));
    if (!a.scene.empty()) fmt::print("{}\n", clearance_words(plan.clearance));
  }
  arm::RunHooks hooks;
  hooks.command = [&] { return interrupted ? arm::MotionCommand::stop : arm::MotionCommand::none; };
  hooks.wait = wait_options(a);
  hooks.wait_for_arrival = a.wait;
  const arm::RunReport report = must(arm::run_motion(*s.arm, plan, hooks));
  if (report.stopped) throw ArmctlError(ErrorKind::device, "stopped by a signal: the arm halted where it was");
  if (!a.wait) {
    if (!a.json) fmt::print("moving\n");
    else print_json_line(json{{"moving", true}});
    return;
  }
  print_arrived(a, s, goal, *report.arrived);
}

void run_joints(const ArmArgs& a) {
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  print_joints(a, s->arm->model(), must(s->arm->read()));
}

// The scene's fence and reduced mode, and whether each is on (with --fence and
// --reduced-mode applied): what every plan of the command is checked with.
void run_limits(const ArmArgs& a) {
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  const scene::Scene sc = s->arm->scene();
  if (a.json) {
    print_json_line(json{{"limits", json::parse(scene::limits_json(sc))}});
    return;
  }
  auto on = [](bool b) { return b ? "on" : "off"; };
  if (const auto& f = sc.fence)
    fmt::print("fence: {}: the tool point{} within x {:.1f}..{:.1f}, y {:.1f}..{:.1f}, z {:.1f}..{:.1f} mm\n", on(f->on),
               f->links ? " and every link" : "", f->low.x() * 1e3, f->high.x() * 1e3, f->low.y() * 1e3,
               f->high.y() * 1e3, f->low.z() * 1e3, f->high.z() * 1e3);
  else
    fmt::print("fence: none (a scene file's \"fence\" sets one: docs/scene.md)\n");
  if (const auto& r = sc.reduced) {
    std::string what = r->tool_speed ? fmt::format("tool speed up to {:.1f} mm/s", *r->tool_speed * 1e3) : "";
    for (const auto& j : r->joints) {
      const auto index = s->arm->model().find_joint(j.joint);
      what += fmt::format("{}{} {:g}..{:g} {}", what.empty() ? "" : "; ", j.joint, j.lower, j.upper,
                          index ? display_unit(s->arm->model().joints[std::size_t(*index)].dimension) : "");
    }
    fmt::print("reduced mode: {}: {}\n", on(r->on), what);
  } else {
    fmt::print("reduced mode: none (a scene file's \"reduced\" sets one: docs/scene.md)\n");
  }
}

void run_pose(const ArmArgs& a) {
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  const motion::JointVector q = s->arm->chain_of(must(s->arm->read()).positions);
  const motion::Pose p = s->arm->forward(q);
  const motion::Rpy rpy = s->arm->tool_rpy(p, q);
  if (a.json) print_json_line(json{{"pose", pose_json(p, rpy)}});
  else fmt::print("{}\n", pose_text(p, rpy));
}

void run_move_joints(const ArmArgs& a) {
  const arm::ArmModel model = session::load_arm(a.arm).value();  // refuse bad words before opening anything
  std::vector<std::optional<double>> targets(std::size_t(model.joint_count()));
  for (const auto& w : a.words) {
    auto [name, value] = split_assignment(w, "JOINT=VALUE (e.g. 2=30deg, SHOULDER=-0.5rad, Z=120mm)");
    const int i = find_joint(model, name);
    const auto& j = model.joints[std::size_t(i)];
    if (targets[std::size_t(i)]) usage(fmt::format("joint {} is given twice", j.name));
    targets[std::size_t(i)] = must(parse_quantity(value, j.dimension, "joint " + j.name));
  }
  arm::PtpMove move = ptp_move(a);
  move.target = targets;
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  must(s->arm->check_targets(targets));
  run_board_move(a, *s, move, std::nullopt);
}

double parse_override(const ArmArgs& a) {
  return percent_option(a.speed_override, "--override (of the programmed speeds)", 1.0);
}

MotionCliOptions motion_cli_options(const ArmArgs& a) { return MotionCliOptions{a.json, parse_override(a)}; }

// move-to --linear: one LIN move, run by the motion layer (host-planned, streamed).
void run_move_linear(const ArmArgs& a) {
  if (!a.time.empty()) usage("--time is not allowed with --linear: give the tool's speed with --speed (e.g. 50mm/s)");
  const arm::CartesianGoal goal = parse_goal(a);
  files::PathMove m;
  m.kind = files::MoveKind::lin;
  m.position = goal.position;
  m.roll = goal.roll;
  m.pitch = goal.pitch;
  m.yaw = goal.yaw;
  if (!a.speed.empty())
    m.speed = must(parse_quantity_in(a.speed, Dimension::length, "--speed", 1, "mm/s", motion::kMinToolSpeed,
                                     motion::kMaxToolSpeed));
  if (!a.zone.empty()) m.zone = must(parse_quantity(a.zone, Dimension::length, "--zone", 0, "mm"));
  if (m.zone < 0) usage(fmt::format("--zone '{}' is not allowed: 0 or more (e.g. 5mm)", a.zone));
  const MotionCliOptions options = motion_cli_options(a);
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  print_arrived(a, *s, goal, run_path_moves(*s, {m}, options));
}

void run_path(const ArmArgs& a) {
  const files::PathFile file = must(files::read_path_file(a.path_file));
  if (file.moves.empty()) usage(fmt::format("{} has no moves", a.path_file));
  MotionCliOptions options = motion_cli_options(a);
  std::optional<MotionTrace> trace;  // opened before anything moves: a bad path is refused first
  if (!a.trace.empty()) options.trace = &trace.emplace(a.trace);
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  const arm::JointState arrived = run_path_moves(*s, file.moves, options);
  if (trace) trace->finish();
  print_arrived(a, *s, std::nullopt, arrived);
}

void run_stop(const ArmArgs& a) {
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  must(s->arm->stop());
  if (a.json) print_json_line(json{{"stopped", true}});
  else fmt::print("stopped\n");
}

// What the dashboard and ROS show of the device's health (ArmDevice::health): the
// supply and every fault the device reports (a Robot Commands board with armctl's
// JointFaultRead, the joint bus's diagnostics); what the device cannot tell is "n/a".
void run_health(const ArmArgs& a) {
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  const arm::DeviceHealth h = s->arm->device().health();
  if (a.json) {
    print_json_line(json{{"health",
                          {{"battery_volts", h.battery_volts ? json(*h.battery_volts) : json(nullptr)},
                           {"faults", h.faults}}}});
    return;
  }
  fmt::print("battery  {}\n", h.battery_volts ? fmt::format("{:.2f} V", *h.battery_volts) : std::string("n/a"));
  if (h.faults.empty()) fmt::print("faults   none\n");
  for (const auto& f : h.faults) fmt::print("fault    {}\n", f);
}

// Clears the faults the joints hold (ArmDevice::clear_faults): each joint holds where it
// is and drives again. Fix the cause first: a joint whose leads are swapped runs away again.
void run_clear_faults(const ArmArgs& a) {
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  must(s->arm->device().clear_faults());
  if (a.json) print_json_line(json{{"faults_cleared", true}});
  else fmt::print("faults cleared\n");
}

void run_move_to(const ArmArgs& a) {
  if (a.linear && a.avoid) usage("--avoid is not allowed with --linear: a line cannot go around (a PTP can)");
  if (!a.avoid && !a.avoid_time.empty()) usage("--avoid-time needs --avoid");
  if (a.linear) return run_move_linear(a);
  if (!a.zone.empty()) usage("--zone needs --linear (a fly-by zone belongs to a Cartesian move)");
  const arm::CartesianGoal goal = parse_goal(a);
  arm::PtpMove move = ptp_move(a);
  move.target = goal;
  avoid_options(a);  // a bad --avoid-time is refused before the device opens
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  run_board_move(a, *s, move, goal);
}

void run_ik(const ArmArgs& a) {
  const arm::CartesianGoal goal = parse_goal(a);
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  const arm::JointState now = must(s->arm->read());
  const auto solutions = must(s->arm->inverse(goal, now));
  const arm::ArmModel& m = s->arm->model();
  json all = json::array();
  for (std::size_t k = 0; k < solutions.size(); ++k) {
    const auto& sol = solutions[k];
    std::string config;
    if (sol.configuration.elbow) config += fmt::format("elbow {}", motion::to_string(*sol.configuration.elbow));
    if (sol.configuration.wrist_flipped) config += *sol.configuration.wrist_flipped ? ", wrist flipped" : "";
    if (sol.configuration.reaching_back && *sol.configuration.reaching_back) config += ", reaching back";
    json js = json::object();
    std::string text;
    for (int i = 0; i < m.chain_joints(); ++i) {
      const auto& j = m.joints[std::size_t(i)];
      js[j.name] = sol.joints[i];
      text += fmt::format("{}={:.3f}{} ", j.name, to_display(j.dimension, sol.joints[i]), display_unit(j.dimension));
    }
    all.push_back({{"joints", js}, {"configuration", config}});
    if (!a.json) fmt::print("solution {}{}: {}{}\n", k + 1, k == 0 ? " (nearest)" : "", text, config.empty() ? "" : "(" + config + ")");
  }
  if (a.json) print_json_line(json{{"solutions", all}});
}

void run_torque(const ArmArgs& a) {
  if (a.onoff != "on" && a.onoff != "off") usage(fmt::format("torque: '{}' is not allowed: on or off", a.onoff));
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  must(s->arm->set_torque(a.onoff == "on"));
  if (a.json) print_json_line(json{{"torque", a.onoff}});
  else fmt::print("torque {}\n", a.onoff);
}

void run_gripper(const ArmArgs& a) {
  double fraction = 0;
  if (a.gripper == "open") fraction = 0;
  else if (a.gripper == "close") fraction = 1;
  else {
    std::string t = a.gripper;
    const bool percent = !t.empty() && t.back() == '%';
    if (percent) t.pop_back();
    double v = 0;
    auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (!percent || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v) || v < 0 || v > 100)
      usage(fmt::format("gripper: '{}' is not allowed: open, close, or how far closed as 0%..100%", a.gripper));
    fraction = v / 100;
  }
  arm::PtpMove move = ptp_move(a);
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  const arm::ArmModel& model = s->arm->model();
  if (!model.gripper) throw ArmctlError(ErrorKind::unsupported, fmt::format("arm '{}' has no gripper", model.name));
  std::vector<std::optional<double>> targets(std::size_t(model.joint_count()));
  targets[std::size_t(model.gripper->joint)] = model.gripper->at(fraction);
  move.target = targets;
  run_board_move(a, *s, move, std::nullopt);
}

void run_calibrate_zero(const ArmArgs& a) {
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  const arm::ArmModel& m = s->arm->model();
  std::vector<int> joints;
  for (const auto& w : a.words) joints.push_back(find_joint(m, w));
  if (joints.empty())
    for (int i = 0; i < m.joint_count(); ++i) joints.push_back(i);
  const arm::JointState now = must(s->arm->read());
  const auto changes = must(arm::calibrate_zero(m, s->arm->device().protocol(), now.device, joints));
  // Through the one calibration writer: one atomic replacement, the previous file kept.
  (void)must(calibration::write_calibration(m, calibration::from_zero_changes(m, changes)));
  for (const auto& c : changes) {
    const auto& j = m.joints[std::size_t(c.joint)];
    if (a.json)
      print_json_line(json{{"joint", j.name}, {"zero_moved_by", c.shift}, {"file", m.file.string()}});
    else
      fmt::print("{}: zero moved by {} (now where it stands), saved in {}\n", j.name, format_quantity(j.dimension, c.shift),
                 m.file.string());
  }
}

}  // namespace

void add_arm_command(CLI::App& app) {
  auto a = std::make_shared<ArmArgs>();
  auto* cmd = app.add_subcommand("arm", "Drive an arm in SI units: joints, tool pose, moves, IK, gripper");
  cmd->footer(
      "Values take units: 30deg, 0.5rad, 120mm, 0.12m (x, y, z default to mm; roll, pitch, yaw to\n"
      "deg). Joints are named (SHOULDER, servo3) or numbered as their device numbers them (the\n"
      "servo ID, the joint-bus number). Without --device: the xArm on an emulated xArm board in\n"
      "this process (servos start at centre every command), the SCARA on an embedded simulated\n"
      "arm on the joint bus. Arm files: docs/arm-files.md.");
  cmd->require_subcommand(1);
  cmd->fallthrough();
  cmd->add_option("--arm", a->arm, "xarm | scara | an arm file (default xarm)");
  cmd->add_option("--device", a->device,
                  "xArm: hid | serial:/dev/X[?baud=N] | /dev/PATH; SCARA: sim[?...] | unix:PATH | "
                  "serial:...&select=... (joint bus) or any Robot Commands URI (arm controller)");
  add_scene_option(cmd, a->scene);
  cmd->add_flag("--json", a->json, "Machine-readable output (one JSON object per line)");

  auto add_motion_options = [a](CLI::App* sub) {
    sub->add_option("--time", a->time, "Move duration: 2s, 800ms, up to 600s (default: from --speed); a time shorter than the arm file's limits allow is stretched to them");
    sub->add_option("--speed", a->speed, "Percent of the joints' velocity limits, 0.1..100% (default 25%)");
    sub->add_flag("--wait", a->wait, "Wait until every joint arrives, then print where it stands");
    sub->add_option("--timeout", a->timeout_s, "With --wait: give up after this many seconds (default 20)")
        ->check(number_in(0.1, 600, "s"));
  };

  cmd->add_subcommand("joints", "Joint positions (deg or mm, and device units)")->callback([a] { run_joints(*a); });
  cmd->add_subcommand("pose", "Tool pose: x y z in mm, roll pitch yaw in deg")->callback([a] { run_pose(*a); });
  cmd->add_subcommand("limits", "The scene's fence and reduced mode, and whether each is on (--scene, --fence, --reduced-mode)")
      ->callback([a] { run_limits(*a); });

  auto* mj = cmd->add_subcommand("move-joints", "Move joints: 2=30deg 1=120mm SHOULDER=-0.5rad");
  mj->add_option("targets", a->words, "JOINT=VALUE with a unit")->required();
  add_motion_options(mj);
  mj->callback([a] { run_move_joints(*a); });

  auto add_goal = [a](CLI::App* sub) {
    sub->add_option("pose", a->words, "x=.. y=.. z=.. [roll=.. pitch=.. yaw=..]")->required();
    sub->add_option("--elbow", a->elbow, "left | right (scara), up | down (xarm)");
    sub->add_flag("--nearest-orientation", a->nearest, "5-joint xArm: the nearest orientation it can reach");
  };
  auto* mt = cmd->add_subcommand("move-to", "Move the tool to a pose (PTP through IK, or --linear along a line)");
  add_goal(mt);
  add_motion_options(mt);
  mt->add_flag("--linear", a->linear,
               "Along a straight line, planned on the host and streamed (--speed is then the tool's, e.g. 50mm/s)");
  mt->add_option("--zone", a->zone, "With --linear: fly-by radius at the end (a single move ends at rest)");
  mt->add_option("--override", a->speed_override, "With --linear: percent of the programmed speed, 0.1..100% (default 100%)");
  mt->add_flag("--avoid", a->avoid,
               "When the direct move would collide, go around: a collision-free joint path (OMPL), streamed");
  mt->add_option("--avoid-time", a->avoid_time, "With --avoid: how long the search may take, 10ms..60s (default 1s)");
  mt->callback([a] { run_move_to(*a); });

  auto* path = cmd->add_subcommand("path", "Run a path file: PTP, LIN and CIRC moves with speeds and fly-by zones");
  path->add_option("file", a->path_file, "Path file (docs/paths.md)")->required();
  path->add_option("--override", a->speed_override, "Percent of the programmed speeds, 0.1..100% (default 100%)");
  path->add_option("--trace", a->trace, "Write the tool's planned and measured positions to FILE (CSV, mm)")
      ->check(trace_file_check());
  path->callback([a] { run_path(*a); });

  cmd->add_subcommand("stop", "Stop every joint where it stands and hold it")->callback([a] { run_stop(*a); });
  cmd->add_subcommand("health", "Supply voltage and joint faults, as the dashboard shows them")
      ->callback([a] { run_health(*a); });
  cmd->add_subcommand("clear-faults",
                      "Clear the faults the joints hold (see health): each holds where it is and drives again")
      ->callback([a] { run_clear_faults(*a); });

  auto* ik = cmd->add_subcommand("ik", "Print every IK solution for a pose; moves nothing");
  add_goal(ik);
  ik->callback([a] { run_ik(*a); });

  auto* torque = cmd->add_subcommand("torque", "Torque on (hold) or off (move by hand)");
  torque->add_option("state", a->onoff, "on | off")->required();
  torque->callback([a] { run_torque(*a); });

  auto* grip = cmd->add_subcommand("gripper", "Gripper: open, close, or N% closed");
  grip->add_option("position", a->gripper, "open | close | 0%..100%")->required();
  add_motion_options(grip);
  grip->callback([a] { run_gripper(*a); });

  auto* cal = cmd->add_subcommand("calibrate", "Calibration of the arm file");
  cal->require_subcommand(1);
  auto* zero = cal->add_subcommand("zero", "Record where the joints stand as their zero, in the arm file");
  zero->add_option("joints", a->words, "Joints to zero (default: all)");
  zero->callback([a] { run_calibrate_zero(*a); });
}

}  // namespace armctl::cli

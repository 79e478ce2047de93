// armctl replay FILE [--arm A] [--device URI] [--speed N%]
// Plays a recording (`armctl teach --record`) back through the motion layer: smoothed,
// decimated into waypoints, one jerk-limited move through them within the arm's limits
// (docs/teach.md "Replay"). Refuses a recording of another arm or outside the limits before
// anything moves. Ctrl-C stops on the path with a controlled deceleration.
#include <string>

#include <fmt/core.h>

#include "session/arm_session.hpp"
#include "apps/armctl/scene_option.hpp"
#include "apps/armctl/commands.hpp"
#include "apps/armctl/json_output.hpp"
#include "apps/armctl/number_options.hpp"
#include "apps/armctl/serve_support.hpp"
#include "arm/run_motion.hpp"
#include "core/error.hpp"
#include "files/recording_file.hpp"
#include "teach/replay.hpp"

namespace armctl::cli {

namespace {

struct ReplayArgs {
  SceneArgs scene;  // --scene FILE, --fence, --reduced-mode
  std::string file;
  std::string arm;
  std::string device;
  std::string speed = "100%";
  bool json = false;
};

void run_replay(const ReplayArgs& a) {
  const double speed = percent_option(a.speed, "--speed (of the velocity limits)", 1.0);
  auto recording = files::read_recording(a.file);
  if (!recording) throw ArmctlError(recording.error());
  // The recording names its arm: the shipped model of that name unless --arm says otherwise.
  auto s = session::open_arm_session(a.arm.empty() ? recording->arm : a.arm, a.device, with_scene(a.scene)).value();
  arm::Arm& arm = *s->arm;
  auto here = arm.read();
  if (!here) throw ArmctlError(here.error());
  teach::ReplayOptions options;
  options.speed = speed;
  auto plan = teach::plan_replay(arm.model(), here->positions, *recording, options);
  if (!plan) throw ArmctlError(Error{plan.error().kind, a.file + ": " + plan.error().message});
  if (a.json)
    print_json_event("planned", {{"file", a.file}, {"samples", recording->samples.size()},
                                 {"recorded_s", plan->recorded_seconds}, {"waypoints", plan->waypoints.size()},
                                 {"to_start_s", plan->to_start.duration}, {"replay_s", plan->motion.duration},
                                 {"speed_percent", speed * 100}});
  else
    fmt::print("{}: {} samples over {:.2f} s -> {} waypoints; to the start {:.2f} s, replay {:.2f} s at {:g} %\n",
               a.file, recording->samples.size(), plan->recorded_seconds, plan->waypoints.size(),
               plan->to_start.duration, plan->motion.duration, speed * 100);
  std::fflush(stdout);

  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);
  arm::RunHooks hooks;
  hooks.command = [&] { return interrupted ? arm::MotionCommand::stop : arm::MotionCommand::none; };
  hooks.on_event = [&](const arm::RunEvent& e) {
    if (e.kind != arm::RunEventKind::piece_done || !e.report) return;
    const arm::MotionReport& report = *e.report;
    const arm::PlannedMotion& m = e.piece->motion;
    const double elapsed = std::chrono::duration<double>(report.elapsed).count();
    const int joint = report.largest_following_joint;
    if (a.json) {
      nlohmann::json j{{"what", m.what}, {"planned_s", m.duration}};
      if (report.stopped) j["reached_s"] = report.t_reached;
      else j["elapsed_s"] = elapsed;
      if (joint >= 0)
        j["largest_following_error"] = {{"joint", arm.model().joints[std::size_t(joint)].name},
                                        {"si", report.largest_following_error}};
      print_json_event(report.stopped ? "stopped" : "done", std::move(j));
      return;
    }
    if (report.stopped) {
      fmt::print("stopped by a signal at {:.2f} of {:.2f} s ({})\n", report.t_reached, m.duration, m.what);
      return;
    }
    fmt::print("{}: done in {:.2f} s, largest following error {}\n", m.what, elapsed,
               joint >= 0 ? arm::format_joint_value(arm.model(), joint, report.largest_following_error)
                          : std::string("none measured"));
  };
  auto report = arm::run_motion(arm, plan->plan, hooks);
  if (!report) throw ArmctlError(report.error());
}

}  // namespace

void add_replay_command(CLI::App& app) {
  auto a = std::make_shared<ReplayArgs>();
  auto* cmd = app.add_subcommand("replay", "Play a recording (armctl teach --record) back through the motion layer");
  cmd->add_option("file", a->file, "Recording file")->required();
  cmd->add_option("--arm", a->arm, "xarm | scara | an arm file (default: the arm the recording names)");
  cmd->add_option("--device", a->device, "As for `armctl arm` (default: the embedded simulated arm)");
  add_scene_option(cmd, a->scene);
  cmd->add_option("--speed", a->speed, "Percent of the velocity limits (default 100%)");
  cmd->add_flag("--json", a->json, "One JSON object per line: planned, then done (or stopped) per motion");
  cmd->callback([a] { run_replay(*a); });
}

}  // namespace armctl::cli

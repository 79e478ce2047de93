// armctl teach [--arm A] [--device URI] --points FILE | --record RATE --out FILE
// Torque off (xArm) or the position loops off (SCARA), the arm moved by hand; each line on
// standard input records a point (docs/teach.md), or --record records a continuous motion.
// Torque comes back on at the end holding the arm where it stands, also on Ctrl-C and errors.
#include <chrono>
#include <string>

#include <fmt/core.h>

#include "session/arm_session.hpp"
#include "apps/armctl/scene_option.hpp"
#include "apps/armctl/arm_json.hpp"
#include "apps/armctl/commands.hpp"
#include "apps/armctl/json_output.hpp"
#include "apps/armctl/serve_support.hpp"
#include "apps/armctl/stdin_lines.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/quantity.hpp"
#include "files/recording_file.hpp"
#include "teach/teach.hpp"

namespace armctl::cli {

namespace {

struct TeachArgs {
  SceneArgs scene;  // --scene FILE, --fence, --reduced-mode
  std::string arm = "xarm";
  std::string device;
  std::string points;
  std::string record;
  std::string out;
  std::string duration;
  bool json = false;
};

[[noreturn]] void usage(const std::string& message) { throw ArmctlError(ErrorKind::invalid_argument, message); }

// "10s", "500ms", "2": seconds of recording.
Duration parse_duration(const std::string& text) {
  std::string digits = text;
  double scale = 1;
  if (digits.size() > 2 && digits.substr(digits.size() - 2) == "ms") {
    digits.resize(digits.size() - 2);
    scale = 1e-3;
  } else if (!digits.empty() && digits.back() == 's') {
    digits.pop_back();
  }
  char* end = nullptr;
  const double v = std::strtod(digits.c_str(), &end);
  if (digits.empty() || end != digits.c_str() + digits.size() || !(v * scale > 0) || v * scale > 24 * 3600)
    usage(fmt::format("--duration '{}': a time above 0 up to 24 h, such as '10s' or '500ms'", text));
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(v * scale));
}

void run_teach(const TeachArgs& a) {
  const bool recording = !a.record.empty();
  if (recording == !a.points.empty())
    usage("teach needs either --points FILE (points, one per line typed) or --record RATE --out FILE");
  if (recording && a.out.empty()) usage("--record needs --out FILE (the recording to write)");
  if (!recording && !a.out.empty()) usage("--out goes with --record; points go to --points FILE");
  if (!recording && !a.duration.empty()) usage("--duration goes with --record");
  double rate = 0;
  if (recording) {
    auto r = files::parse_rate(a.record);
    if (!r) usage("--record: " + r.error().message);
    rate = *r;
  }
  std::optional<Duration> duration;
  if (!a.duration.empty()) duration = parse_duration(a.duration);

  // The recording is made by hand and cannot be made again: where it goes is checked
  // before the arm is even opened (no such directory, a read-only file).
  if (recording)
    if (auto w = check_writable(a.out); !w)
      throw ArmctlError(w.error().kind, w.error().message + "; nothing recorded, torque not switched off");
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  arm::Arm& arm = *s->arm;
  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);
  StdinLines input(interrupted.flag);
  // A line for a person, or under --json one JSON object per event.
  auto say = [&](const std::string& event, nlohmann::json fields, const std::string& text) {
    if (a.json) {
      print_json_event(event.c_str(), std::move(fields));
      return;
    }
    fmt::print("{}\n", text);
    std::fflush(stdout);
  };

  if (!recording) {
    auto on_event = [&](const teach::TeachEvent& e) {
      nlohmann::json fields = nlohmann::json::object();
      switch (e.kind) {
        case teach::TeachEventKind::started: fields["points_file"] = a.points; break;
        case teach::TeachEventKind::recorded:
        case teach::TeachEventKind::replaced:
          fields = {{"point", e.name}, {"joints", joint_values_json(arm.model(), e.positions)}};
          break;
        case teach::TeachEventKind::refused: fields = {{"point", e.name}, {"message", e.text}}; break;
        case teach::TeachEventKind::finished: fields = {{"points", e.points}, {"points_file", a.points}}; break;
      }
      say(teach::to_string(e.kind), std::move(fields), e.text);
    };
    teach::TeachIo io{[&] { return input.next(); }, on_event};
    auto n = teach::teach_points(arm, a.points, io);
    if (!n) throw ArmctlError(n.error());
    return;
  }
  teach::RecordOptions o;
  o.rate = rate;
  o.duration = duration;
  // With --duration the input's end does not stop the recording (a script may have none).
  o.done = [&] {
    if (interrupted) return true;
    if (input.line_ready()) return true;
    return !duration && input.ended();
  };
  o.on_start = [&] {
    say("started",
        {{"rate_hz", rate},
         {"duration_s", duration ? nlohmann::json(std::chrono::duration<double>(*duration).count()) : nlohmann::json()}},
        fmt::format("torque off: move the arm by hand; recording at {:g} Hz until {}", rate,
                    duration ? fmt::format("{:g} s have passed (or Ctrl-C)", std::chrono::duration<double>(*duration).count())
                             : std::string("Enter, the end of input or Ctrl-C")));
  };
  auto r = teach::record_motion(arm, o);
  if (!r) throw ArmctlError(r.error());
  if (auto w = files::write_recording(a.out, *r); !w) throw ArmctlError(w.error());
  say("finished", {{"samples", r->samples.size()}, {"seconds", r->samples.back().time}, {"file", a.out}},
      fmt::format("torque on, holding; {} samples over {:.2f} s written to {}", r->samples.size(),
                  r->samples.back().time, a.out));
}

}  // namespace

void add_teach_command(CLI::App& app) {
  auto a = std::make_shared<TeachArgs>();
  auto* cmd = app.add_subcommand("teach", "Move the arm by hand (torque off) and record points or a motion (docs/teach.md)");
  add_arm_options(cmd, a->arm, a->device);
  add_scene_option(cmd, a->scene);
  cmd->add_option("--points", a->points, "Points file to add the points to (written after each point)");
  cmd->add_option("--record", a->record, "Record a continuous motion at this rate instead (e.g. 20Hz)");
  cmd->add_option("--out", a->out, "With --record: the recording file to write");
  cmd->add_option("--duration", a->duration, "With --record: stop after this long (e.g. 10s)");
  cmd->add_flag("--json", a->json, "One JSON object per line for each event (started, recorded, refused, finished)");
  cmd->callback([a] { run_teach(*a); });
}

}  // namespace armctl::cli

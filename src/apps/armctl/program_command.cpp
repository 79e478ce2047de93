// armctl program check|run|compile FILE: robot programs (docs/programs.md). Every command
// first checks the whole program on the planner (every point resolves, every move
// reachable and inside the joint limits along its whole path, from where the arm stands);
// nothing moves unless all of it passes.
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "session/arm_session.hpp"
#include "apps/armctl/clearance_words.hpp"
#include "apps/armctl/scene_option.hpp"
#include "apps/armctl/commands.hpp"
#include "apps/armctl/number_options.hpp"
#include "apps/armctl/json_output.hpp"
#include "apps/armctl/motion_trace.hpp"
#include "apps/armctl/serve_support.hpp"
#include "apps/armctl/xarm_args.hpp"
#include "core/error.hpp"
#include "core/must.hpp"
#include "core/printable.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"
#include "program/group_compiler.hpp"
#include "files/points_file.hpp"
#include "program/program_flow.hpp"
#include "program/program_load.hpp"
#include "program/program_parser.hpp"
#include "program/program_plan.hpp"
#include "program/program_runner.hpp"

namespace armctl::cli {

namespace {

using nlohmann::json;

struct ProgramArgs {
  SceneArgs scene;  // --scene FILE, --fence, --reduced-mode
  std::string file;
  std::string arm = "xarm";
  std::string device;
  std::string points;
  bool json = false;
  std::string speed_override;
  bool step = false;
  bool dry_run = false;
  std::string group;
  std::string path_error;
  std::string trace;  // run --trace FILE
  bool avoid = false;      // check/run --avoid
  std::string avoid_time;  // --avoid-time
};

[[noreturn]] void usage(const std::string& message) { throw ArmctlError(ErrorKind::invalid_argument, message); }


using Loaded = program::LoadedProgram;

Loaded load(const ProgramArgs& a) { return must(program::load_program(a.file, a.points)); }

program::ProgramPlan plan(const ProgramArgs& a, const Loaded& l, arm::Arm& arm, bool blend) {
  const auto here = must(arm.read());
  program::PlanOptions o;
  o.blend = blend;
  if (a.avoid) o.avoid.emplace().time_budget = avoid_time_option(a.avoid_time, 1.0);
  return must(program::plan_program(*arm.kinematics(), here.positions, l.flow, l.program.source, o));
}

void print_check(const ProgramArgs& a, const Loaded& l, const program::ProgramPlan& p, const arm::Arm& arm) {
  if (a.json) {
    json pieces = json::array();
    for (const auto& piece : p.pieces)
      pieces.push_back({{"line", piece.first_line},
                        {"last_line", piece.last_line},
                        {"what", piece.label},
                        {"seconds", piece.kind == program::PieceKind::motion ? piece.motion.duration : piece.seconds}});
    json checked{{"event", "checked"}, {"arm", arm.model().name}, {"moves", p.moves},
                 {"pieces", pieces}, {"statements", l.flow.statements}, {"duration_s", p.duration}};
    add_clearance_json(checked, p.clearance);
    print_json_line(checked);
    return;
  }
  for (const auto& piece : p.pieces) {
    if (piece.kind == program::PieceKind::message) continue;
    fmt::print("  {:<60} {:7.2f} s\n", piece.label,
               piece.kind == program::PieceKind::motion ? piece.motion.duration : piece.seconds);
  }
  fmt::print("{}: OK on arm '{}': {} move{} in {} piece{}, {} statements run; estimated run time {:.1f} s at 100 %\n",
             l.program.source, arm.model().name, p.moves, p.moves == 1 ? "" : "s", p.pieces.size(),
             p.pieces.size() == 1 ? "" : "s", l.flow.statements, p.duration);
  if (!a.scene.empty()) fmt::print("{}\n", clearance_words(p.clearance));
}

void run_check(const ProgramArgs& a) {
  const Loaded l = load(a);
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  const auto p = plan(a, l, *s->arm, true);
  print_check(a, l, p, *s->arm);
}

void run_run(const ProgramArgs& a) {
  if (a.dry_run && !a.device.empty())
    usage("--dry-run runs on the embedded simulated arm: leave out --device (or drop --dry-run to run on it)");
  const double speed_override = percent_option(a.speed_override, "--override (of the programmed speeds)", 1.0);
  const Loaded l = load(a);
  std::optional<MotionTrace> trace;  // opened before anything moves: a bad path is refused first
  if (!a.trace.empty()) trace.emplace(a.trace);
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  arm::Arm& arm = *s->arm;
  const auto p = plan(a, l, arm, !a.step);  // refuses before anything moves
  // The estimate at the override the run uses (it said 81.8 s for a run of 164.4 s at 50 %).
  const double estimate = program::estimated_duration(p, speed_override);
  if (a.json) {
    json planned{{"event", "planned"}, {"moves", p.moves}, {"pieces", p.pieces.size()}, {"duration_s", estimate}, {"dry_run", a.dry_run}};
    add_clearance_json(planned, p.clearance);
    print_json_line(planned);
  } else {
    if (!a.scene.empty()) fmt::print("{}\n", clearance_words(p.clearance));
    fmt::print("{}planned {} move{} ({} piece{}), about {:.1f} s{}\n", a.dry_run ? "dry run on the simulated arm: " : "",
               p.moves, p.moves == 1 ? "" : "s", p.pieces.size(), p.pieces.size() == 1 ? "" : "s", estimate,
               speed_override < 1 ? fmt::format(" at {:g} %", speed_override * 100) : std::string());
  }
  std::fflush(stdout);

  Interrupted interrupted;
  StopOnSignals on_signals(interrupted);
  const bool progress_line = !a.json && isatty(STDERR_FILENO);
  program::RunOptions o;
  o.speed_override = speed_override;
  o.command = [&] { return interrupted ? arm::MotionCommand::stop : arm::MotionCommand::none; };
  if (a.step)
    o.before_piece = [&](const program::PlannedPiece& piece) {
      fmt::print(stderr, "{}: Enter to run it, q then Enter to stop: ", piece.label);
      std::fflush(stderr);
      std::string line;
      if (!std::getline(std::cin, line) || line == "q") return false;
      return true;
    };
  o.on_event = [&](const program::RunEvent& e) {
    const auto& piece = *e.piece;
    if (trace && e.kind == program::RunEventKind::piece_done && e.report)
      trace->add(arm, piece.first_line, piece.motion, *e.report);
    if (a.json) {
      json j{{"line", piece.first_line}, {"what", piece.label}, {"left_s", e.left}};
      switch (e.kind) {
        case program::RunEventKind::piece_started: j["event"] = "line"; break;
        case program::RunEventKind::progress: j["event"] = "progress"; break;
        case program::RunEventKind::message: j["event"] = "print"; j["text"] = piece.text; break;
        case program::RunEventKind::piece_done:
          j["event"] = e.report && !e.report->completed ? "stopped" : "done";
          if (e.report) {
            j["elapsed_s"] = std::chrono::duration<double>(e.report->elapsed).count();
            j["points"] = e.report->points;
            j["following_error"] = e.report->largest_following_error;
          }
          break;
      }
      print_json_line(j);
      std::fflush(stdout);
      return;
    }
    if (e.kind == program::RunEventKind::message) {
      if (progress_line) fmt::print(stderr, "\r\033[K");
      fmt::print("line {}: {}\n", piece.first_line, printable(piece.text));
      std::fflush(stdout);
    } else if (e.kind == program::RunEventKind::piece_done) {
      if (progress_line) fmt::print(stderr, "\r\033[K");
      if (e.report)
        fmt::print("{}: {} in {:.2f} s\n", piece.label, e.report->completed ? "done" : "stopped",
                   std::chrono::duration<double>(e.report->elapsed).count());
      else
        fmt::print("{}: done\n", piece.label);
      std::fflush(stdout);
    } else if (progress_line) {
      fmt::print(stderr, "\r\033[K{}: {:.1f} s left", piece.label, e.left);
    }
  };
  const auto report = must(program::run_plan(arm, p, o));
  if (trace) trace->finish();
  if (progress_line) fmt::print(stderr, "\r\033[K");
  const double elapsed = std::chrono::duration<double>(report.elapsed).count();
  if (a.json)
    print_json_line(json{{"event", report.completed ? "finished" : "stopped"}, {"elapsed_s", elapsed},
                            {"pieces", report.pieces}});
  else if (report.completed)
    fmt::print("finished in {:.1f} s\n", elapsed);
  std::fflush(stdout);
  if (!report.completed)
    throw ArmctlError(ErrorKind::device, fmt::format("stopped after {} of {} pieces{} (the arm is at rest)", report.pieces,
                                                     p.pieces.size(), interrupted ? " by a signal" : ""));
}

void run_compile(const ProgramArgs& a) {
  const auto group = xarm_args::parse_group(a.group, false);
  program::CompileOptions co;
  if (!a.path_error.empty()) {
    co.path_error = must(parse_quantity(a.path_error, Dimension::length, "--path-error", 0, "mm"));
    if (!(co.path_error >= 1e-4 && co.path_error <= 0.05))
      usage(fmt::format("--path-error '{}' is not allowed: 0.1mm up to 50mm", a.path_error));
  }
  const Loaded l = load(a);
  auto s = session::open_arm_session(a.arm, a.device, with_scene(a.scene)).value();
  arm::ActionGroups* groups = s->arm->device().action_groups();
  if (!groups)
    usage(fmt::format("arm '{}' on device '{}' is driven over the joint bus: action groups need a Robot Commands "
                      "board (an xArm, or armctl's arm controller)",
                      s->arm->model().name, a.device.empty() ? "sim" : a.device));
  const auto p = plan(a, l, *s->arm, true);
  const auto g = must(program::compile_to_group(*s->arm, p, co));
  if (auto ok = groups->download(group, g.actions); !ok) throw ArmctlError(ok.error());
  for (const auto& n : g.notes) fmt::print(stderr, "note: {}\n", n);
  if (a.json)
    print_json_line(json{{"event", "compiled"}, {"group", group}, {"actions", g.actions.size()},
                            {"duration_s", g.duration}, {"path_error_mm", co.path_error * 1e3},
                            {"sampling_error_mm", g.sampling_error * 1e3}});
  else
    fmt::print("group {}: {} actions downloaded, {:.1f} s; sampled within {:.2f} mm of the plan (allowed {:.2f} mm), "
               "replay with: armctl xarm group run {}\n",
               group, g.actions.size(), g.duration, g.sampling_error * 1e3, co.path_error * 1e3, group);
}

}  // namespace

void add_program_command(CLI::App& app) {
  auto a = std::make_shared<ProgramArgs>();
  auto* cmd = app.add_subcommand("program", "Robot programs: check, run or compile a program file (docs/programs.md)");
  cmd->require_subcommand(1);
  cmd->footer(
      "A program moves to named points kept in a points file (--points, default: the program's\n"
      "name with .points). Every command checks the whole program first, from where the arm\n"
      "stands: nothing moves unless every move is reachable and inside the joint limits.");
  auto common = [a](CLI::App* sub) {
    sub->add_option("file", a->file, "Program file")->required();
    add_arm_options(sub, a->arm, a->device);
    add_scene_option(sub, a->scene);
    sub->add_option("--points", a->points, "Points file (default: FILE with .points, if it exists)");
    sub->add_flag("--json", a->json, "Machine-readable output (one JSON object per line)");
  };
  auto add_avoid = [a](CLI::App* sub) {
    sub->add_flag("--avoid", a->avoid,
                  "A PTP whose direct move would collide goes around the obstacles (a collision-free joint path, OMPL)");
    sub->add_option("--avoid-time", a->avoid_time, "With --avoid: how long each search may take, 10ms..60s (default 1s)");
  };
  auto* check = cmd->add_subcommand("check", "Check every move before anything moves; estimate the run time");
  common(check);
  add_avoid(check);
  check->callback([a] { run_check(*a); });
  auto* run = cmd->add_subcommand("run", "Check, then run the program");
  common(run);
  add_avoid(run);
  run->add_option("--override", a->speed_override, "Percent of the programmed speeds, 0.1..100% (default 100%)");
  run->add_flag("--step", a->step, "Wait for Enter before each move (moves are not blended)");
  run->add_flag("--dry-run", a->dry_run, "Run on the embedded simulated arm and print what would happen");
  run->add_option("--trace", a->trace, "Write the tool's planned and measured positions to FILE (CSV, mm)")
      ->check(trace_file_check());
  run->callback([a] { run_run(*a); });
  auto* compile = cmd->add_subcommand("compile", "Compile to a Robot Commands action group and download it");
  common(compile);
  compile->add_option("--group", a->group, "Group number 0..254")->required();
  compile->add_option("--path-error", a->path_error, "Largest tool distance from the plan (default 1mm)");
  compile->callback([a] { run_compile(*a); });
}

}  // namespace armctl::cli

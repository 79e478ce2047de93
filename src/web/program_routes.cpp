// Programs from the page's editor (docs/programs.md): check (errors at their line), run
// (on the worker, progress in state.program), pause, resume, stop.
#include <fmt/core.h>

#include "core/source_place.hpp"
#include "program/program_runner.hpp"
#include "web/api_error.hpp"
#include "web/program_check.hpp"
#include "web/request_body.hpp"
#include "web/server_state.hpp"

namespace armctl::web {

namespace {

// A placed error as the Error a refusal returns: "file:line:column: message" ("file:line:"
// without a column), the place its detail; an error at line 0 is the message alone.
// A collision stays the detail (the place's cause) for the page to draw.
Error placed_error(const PlacedError& e) {
  std::any collision = e.collision ? std::any(*e.collision) : std::any{};
  if (!e.line) return Error{ErrorKind::invalid_argument, e.message, std::move(collision)};
  return source_error(ErrorKind::invalid_argument, {e.file, e.line, e.column, e.message, std::move(collision)});
}

// The program run as a worker job: planned from a fresh read (accepted or refused with
// placed errors), then run with the job's context so that pause, resume and stop reach it.
MotionJob program_job(WebServer::State& s, ProgramRequest request) {
  return [&s, request](arm::Arm& arm, session::JobContext& ctx, const Accept& accept) -> Status {
    auto here = arm.read();
    if (!here) return here.error();
    CheckedProgram checked = check_program(request, arm.kinematics().get(), here->positions);
    if (!checked.plan) {
      return placed_error(checked.errors.front());
    }
    const program::ProgramPlan& plan = *checked.plan;
    s.program.started();
    if (plan.pieces.empty()) s.program.at(0, 0, 0);
    else s.program.at(plan.pieces.front().first_line, plan.pieces.front().first_column, plan.duration / request.speed);
    accept(json{{"started", true}, {"duration_s", plan.duration / request.speed}});
    program::RunOptions o;
    o.speed_override = request.speed;
    o.executor = ctx.executor_options();
    o.wait = ctx.wait_options();
    // Waits and the gaps between pieces see only stop (pause and resume are the
    // executor's: they hold a motion on its path).
    o.command = [&ctx] { return ctx.stopping() ? arm::MotionCommand::stop : arm::MotionCommand::none; };
    o.on_event = [&s](const program::RunEvent& e) {
      if (e.kind == program::RunEventKind::message) s.program.print(e.piece->text);
      s.program.at(e.piece->first_line, e.piece->first_column, e.left);
    };
    auto report = program::run_plan(arm, plan, o);
    s.program.ended();
    if (!report) return report.error();
    return Ok{};
  };
}

void require_running(WebServer::State& s) {
  auto v = s.program.view();
  if (!v || v->state == ProgramState::idle) throw ApiError(409, "no program is running");
}

}  // namespace

void add_program_routes(WebServer::State& s) {
  s.router.add("POST", "/api/v1/program/check", [&s](Call& c) {
    const ProgramRequest r = parse_program_request(c.body(), false);
    const auto snapshot = s.worker.snapshot();
    if (snapshot.positions.size() != s.worker.model().joints.size())
      throw ApiError(500, fmt::format("no positions read from the arm yet{}",
                                      snapshot.link_error.empty() ? "" : ": " + snapshot.link_error));
    // Planned from the last positions the worker published (a check moves nothing).
    const CheckedProgram checked = check_program(r, &s.kinematics(), snapshot.positions);
    json out{{"ok", checked.errors.empty()}, {"errors", errors_json(checked.errors, s.worker.model())}};
    out["duration_s"] = checked.plan ? json(checked.plan->duration) : json(nullptr);
    c.reply(out);
  });
  s.router.add("POST", "/api/v1/program/run", [&s](Call& c) {
    s.lease.require(c.client);
    const ProgramRequest r = parse_program_request(c.body(), true);
    // The text's own errors before the arm is asked anything.
    const CheckedProgram text = check_program(r, nullptr, {});
    if (!text.errors.empty()) {
      c.reply({{"error", placed_error(text.errors.front()).message}, {"errors", errors_json(text.errors, s.worker.model())}}, 400);
      return;
    }
    try {
      c.reply(s.start_motion("program", program_job(s, r)), 202);
    } catch (const ApiError& e) {
      if (e.status() != 400) throw;
      const PlacedError placed = e.error() ? place_error(*e.error()) : PlacedError{kProgramSource, 0, 0, e.what()};
      c.reply({{"error", e.what()}, {"errors", errors_json({placed}, s.worker.model())}}, 400);
    }
  });
  s.router.add("POST", "/api/v1/program/pause", [&s](Call& c) {
    s.lease.require(c.client);
    parse_empty_request(c.body());
    require_running(s);
    s.worker.command(arm::MotionCommand::pause);
    s.program.paused(true);
    c.reply({{"paused", true}});
  });
  s.router.add("POST", "/api/v1/program/resume", [&s](Call& c) {
    s.lease.require(c.client);
    parse_empty_request(c.body());
    require_running(s);
    s.worker.command(arm::MotionCommand::resume);
    s.program.paused(false);
    c.reply({{"paused", false}});
  });
  s.router.add("POST", "/api/v1/program/stop", [&s](Call& c) {
    s.lease.require(c.client);
    parse_empty_request(c.body());
    s.worker.command(arm::MotionCommand::stop);
    c.reply({{"stopped", true}});
  });
}

}  // namespace armctl::web

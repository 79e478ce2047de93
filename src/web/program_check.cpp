#include "web/program_check.hpp"

#include "core/source_place.hpp"
#include "files/points_file.hpp"
#include "program/program_flow.hpp"
#include "program/program_parser.hpp"
#include "web/error_detail.hpp"

namespace armctl::web {

PlacedError place_error(const Error& e) {
  PlacedError out{kProgramSource, 0, 0, e.message};
  if (const SourcePlace* at = source_place(e)) out = {at->file, at->line, at->column, at->reason};
  if (const auto* c = detail_or_cause<arm::CollisionDetail>(e)) out.collision = *c;
  return out;
}

CheckedProgram check_program(const ProgramRequest& r, const arm::ArmKinematics* arm, const std::vector<double>& start) {
  CheckedProgram out;
  auto fail = [&](const Error& e) {
    out.errors.push_back(place_error(e));
    return out;
  };
  auto points = files::parse_points_file(r.points, kPointsSource);
  if (!points) return fail(points.error());
  auto parsed = program::parse_program(r.source, kProgramSource);
  if (!parsed) return fail(parsed.error());
  auto flow = program::run_flow(*parsed, *points);
  if (!flow) return fail(flow.error());
  if (arm == nullptr) return out;
  program::PlanOptions options;
  if (r.avoid_time) options.avoid.emplace().time_budget = *r.avoid_time;
  auto plan = program::plan_program(*arm, start, *flow, kProgramSource, options);
  if (!plan) return fail(plan.error());
  out.plan = std::move(plan).value();
  return out;
}

nlohmann::json errors_json(const std::vector<PlacedError>& errors, const arm::ArmModel& model) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : errors) {
    nlohmann::json one{{"file", e.file}, {"line", e.line}, {"column", e.column}, {"message", e.message}};
    if (e.collision) one["collision"] = collision_json(*e.collision, model);
    out.push_back(std::move(one));
  }
  return out;
}

}  // namespace armctl::web

#include "web/program_check.hpp"

#include <charconv>

#include "program/points_file.hpp"
#include "program/program_flow.hpp"
#include "program/program_parser.hpp"

namespace armctl::web {

namespace {

// A whole number at the start of `text` followed by ':', consumed.
std::optional<std::size_t> number_then_colon(std::string_view& text) {
  std::size_t n = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end == text.data() || end == text.data() + text.size() || *end != ':') return std::nullopt;
  text.remove_prefix(std::size_t(end - text.data()) + 1);
  return n;
}

}  // namespace

PlacedError place_error(const std::string& message) {
  for (const char* file : {kProgramSource, kPointsSource}) {
    const std::string prefix = std::string(file) + ":";
    if (message.rfind(prefix, 0) != 0) continue;
    std::string_view rest(message);
    rest.remove_prefix(prefix.size());
    PlacedError e{file, 0, 0, ""};
    if (auto line = number_then_colon(rest)) {
      e.line = *line;
      if (auto column = number_then_colon(rest)) e.column = *column;
    }
    while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
    e.message = std::string(rest);
    return e;
  }
  return {kProgramSource, 0, 0, message};
}

CheckedProgram check_program(const ProgramRequest& r, const arm::ArmKinematics* arm, const std::vector<double>& start) {
  CheckedProgram out;
  auto fail = [&](const Error& e) {
    out.errors.push_back(place_error(e.message));
    return out;
  };
  auto points = program::parse_points_file(r.points, kPointsSource);
  if (!points) return fail(points.error());
  auto parsed = program::parse_program(r.source, kProgramSource);
  if (!parsed) return fail(parsed.error());
  auto flow = program::run_flow(*parsed, *points);
  if (!flow) return fail(flow.error());
  if (arm == nullptr) return out;
  auto plan = program::plan_program(*arm, start, *flow, kProgramSource);
  if (!plan) return fail(plan.error());
  out.plan = std::move(plan).value();
  return out;
}

nlohmann::json errors_json(const std::vector<PlacedError>& errors) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : errors)
    out.push_back({{"file", e.file}, {"line", e.line}, {"column", e.column}, {"message", e.message}});
  return out;
}

}  // namespace armctl::web

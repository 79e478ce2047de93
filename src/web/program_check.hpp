// A program sent by the page (its text and its points file's text): parsed, its flow run,
// every move planned on the arm from where it stands, with every error placed at its line
// and column for the editor. The parser's and planner's errors start "program:LINE:COLUMN:"
// (or "points:..." for the points file); this splits them apart. Pure code on the Arm
// API's const calls.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "arm/arm.hpp"
#include "arm/collision_detail.hpp"
#include "program/program_plan.hpp"
#include "web/request_body.hpp"

namespace armctl::web {

inline constexpr const char* kProgramSource = "program";
inline constexpr const char* kPointsSource = "points";

struct PlacedError {
  std::string file;  // "program" or "points"
  std::size_t line = 0, column = 0;  // 0: not known
  std::string message;  // without the place
  // The line's move would collide or break a limit of the scene: the page draws it.
  std::optional<arm::CollisionDetail> collision{};
};

// An error's place from its SourcePlace detail ({program, 12, 5, "found ..."}); an error
// without one is placed in the program at line 0.
PlacedError place_error(const Error& error);

struct CheckedProgram {
  std::vector<PlacedError> errors;  // empty: ok
  std::optional<program::ProgramPlan> plan;
};

// Parse, flow, and (with `arm` and `start`) plan.
CheckedProgram check_program(const ProgramRequest& request, const arm::ArmKinematics* arm, const std::vector<double>& start);

// [{file, line, column, message, collision?}], a collision as error_detail.hpp's.
nlohmann::json errors_json(const std::vector<PlacedError>& errors, const arm::ArmModel& model);

}  // namespace armctl::web

// One JSON document on one line of standard output, as every `--json` output of armctl is
// (README "Exit status" for errors). Text that is not UTF-8 (a device path, a file's bytes) is
// written with U+FFFD in place of its bad bytes instead of failing the command.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

namespace armctl::cli {

// A number as people read it: 12 significant digits, so that 30 deg converted to rad and
// back prints as 30.0, not 29.999999999999996 (far finer than any joint or sensor resolves).
inline double tidy_number(double v) {
  if (!std::isfinite(v) || v == 0) return v;
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", v);
  return std::strtod(text, nullptr);
}

inline nlohmann::json tidy_numbers(nlohmann::json j) {
  if (j.is_number_float()) return tidy_number(j.get<double>());
  if (j.is_structured())
    for (auto& item : j) item = tidy_numbers(std::move(item));
  return j;
}

inline std::string json_text(const nlohmann::json& j) {
  return tidy_numbers(j).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

inline void print_json_line(const nlohmann::json& j) { fmt::print("{}\n", json_text(j)); }

// {"event": event, ...fields} on one line, flushed: what commands that report as they go
// (teach, replay, the servers, program run) print per event under --json.
inline void print_json_event(const char* event, nlohmann::json fields) {
  if (!fields.is_object()) fields = nlohmann::json::object();
  fields["event"] = event;
  print_json_line(fields);
  std::fflush(stdout);
}

}  // namespace armctl::cli

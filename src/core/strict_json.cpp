#include "core/strict_json.hpp"

#include <optional>
#include <set>
#include <vector>

#include <fmt/core.h>

#include "core/printable.hpp"

namespace armctl {

namespace {

// Thrown from the parser's callback to end the parse at the first problem.
struct Refused {
  JsonProblem problem;
  std::string message;
};

}  // namespace

Result<nlohmann::json> parse_strict_json(std::string_view text, int max_depth) {
  using json = nlohmann::json;
  std::vector<std::set<std::string>> open_objects;
  try {
    return json::parse(text, [&](int depth, json::parse_event_t event, json& parsed) {
      if (depth > max_depth)
        throw Refused{JsonProblem::too_deep, fmt::format("nested deeper than {} levels (the most allowed)", max_depth)};
      if (event == json::parse_event_t::object_start) {
        open_objects.emplace_back();
      } else if (event == json::parse_event_t::object_end) {
        if (!open_objects.empty()) open_objects.pop_back();
      } else if (event == json::parse_event_t::key && !open_objects.empty()) {
        const std::string& key = parsed.get_ref<const std::string&>();
        if (!open_objects.back().insert(key).second)
          throw Refused{JsonProblem::key_twice, fmt::format("key \"{}\" appears twice in one object (each key may appear once)",
                                    printable(key.substr(0, 60)))};
      }
      return true;
    });
  } catch (const Refused& r) {
    return Error{ErrorKind::invalid_argument, r.message, r.problem};
  } catch (const json::exception& e) {
    // Any json::exception: a number too large for a double ("1e400") is an out_of_range.
    return Error{ErrorKind::invalid_argument, fmt::format("not valid JSON: {}", printable(e.what())), JsonProblem::syntax};
  }
}

}  // namespace armctl

// Parsing JSON from outside (HTTP bodies, config files) strictly: nlohmann's parser keeps the
// last of two equal keys, so `{"speed": 10, "speed": 900}` would pass a reviewer's eye with
// the first value and move with the second; and it recurses once per nesting level. Both are
// refused here, once for every reader.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace armctl {

// The Error detail of a refusal: which rule the text broke.
enum class JsonProblem { syntax, key_twice, too_deep };

// The document, or an Error(invalid_argument, detail JsonProblem) whose message says what was wrong, without a
// prefix naming the source (callers add theirs): "key \"speed\" appears twice in one object
// (each key may appear once)", "nested deeper than 32 levels (the most allowed)", "not valid
// JSON: ...". A number too large for a double is refused too (nlohmann's out_of_range).
Result<nlohmann::json> parse_strict_json(std::string_view text, int max_depth);

}  // namespace armctl

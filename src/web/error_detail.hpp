// An error's typed detail as the HTTP API shows it beside the message (docs/http-api.md
// "Errors"): a move refused because it would collide names the two bodies (link or scene
// object, by name), where they touch and how deep, so that the dashboard draws them red
// without reading the message.
#pragma once

#include <nlohmann/json.hpp>

#include "arm/arm_model.hpp"
#include "arm/collision_detail.hpp"
#include "core/error.hpp"

namespace armctl::web {

// {"bodies": [{"kind": "link"|"object", "name", "text"}, ...], "point": [x, y, z] mm (base
// frame, where they touch), "depth_mm", "tool_point": [x, y, z] mm, "fraction" 0..1,
// "line" (of a program; null when not from one), "while_moving", "joints": {name: deg or
// mm} (where the arm would be at the contact: a page draws it there)}.
nlohmann::json collision_json(const arm::CollisionDetail& d, const arm::ArmModel& model);

// Adds the error's detail to an error answer's body: "collision" for a CollisionDetail.
void add_error_detail(nlohmann::json& body, const Error& error, const arm::ArmModel& model);

}  // namespace armctl::web

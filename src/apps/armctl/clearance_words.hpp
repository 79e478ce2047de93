// How the CLI reports a plan's smallest clearance (docs/scene.md): a line for people, the
// same as JSON fields for programs.
#pragma once

#include <optional>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "scene/collision_world.hpp"

namespace armctl::cli {

inline std::string clearance_words(const std::optional<scene::Clearance>& c) {
  if (!c) return "no collision model: not checked for collisions";
  if (c->first.empty()) return fmt::format("no collision: more than {:.0f} mm from everything", scene::kClearanceHorizon * 1e3);
  return fmt::format("no collision: smallest clearance {:.1f} mm, {} to {}", c->distance * 1e3, c->first, c->second);
}

// {"clearance_mm": 12.3, "clearance_between": [a, b]}; the horizon and [] when nothing is
// nearer; nothing when there is no collision model.
inline void add_clearance_json(nlohmann::json& event, const std::optional<scene::Clearance>& c) {
  if (!c) return;
  event["clearance_mm"] = c->distance * 1e3;
  event["clearance_between"] = c->first.empty() ? nlohmann::json::array() : nlohmann::json::array({c->first, c->second});
}

}  // namespace armctl::cli

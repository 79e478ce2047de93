// Joint values as every `--json` output of armctl writes them: per joint its name, the SI
// value and unit, and the value as shown to people (deg, mm).
#pragma once

#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "arm/arm_model.hpp"
#include "core/quantity.hpp"

namespace armctl::cli {

inline nlohmann::json joint_values_json(const arm::ArmModel& m, const std::vector<double>& positions) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < m.joints.size() && i < positions.size(); ++i) {
    const auto& j = m.joints[i];
    out.push_back({{"name", j.name},
                   {"si", positions[i]},
                   {"unit", j.dimension == Dimension::angle ? "rad" : "m"},
                   {"shown", to_display(j.dimension, positions[i])},
                   {"shown_unit", display_unit(j.dimension)}});
  }
  return out;
}

}  // namespace armctl::cli

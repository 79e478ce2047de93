// The shipped arm files and URDFs (config/), as text and as editable JSON, for tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "arm/arm_model.hpp"

namespace armctl::arm::testing {

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
inline std::string config_path(const std::string& name) { return std::string(ARMCTL_SOURCE_DIR) + "/config/" + name; }
inline nlohmann::json arm_json(const std::string& arm) {
  return nlohmann::json::parse(read_text(config_path(arm + ".arm.json")));
}
inline std::string urdf_text(const std::string& arm) { return read_text(config_path(arm + ".urdf")); }

inline Result<ArmModel> parse(const std::string& arm, const nlohmann::json& doc) {
  return parse_arm_model(doc.dump(), arm + ".arm.json", urdf_text(arm), arm + ".urdf");
}
inline ArmModel shipped(const std::string& arm) { return load_arm_model(config_path(arm + ".arm.json")).value(); }

}  // namespace armctl::arm::testing

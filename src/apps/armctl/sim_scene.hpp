// --scene FILE on `armctl sim xarm` and `armctl sim scara`: the simulated arm meets what the
// file puts around it and stalls at contact, whatever drives it (docs/scene.md "Simulators").
#pragma once

#include <functional>
#include <span>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "arm/arm_model.hpp"
#include "arm/scene_obstacle.hpp"
#include "core/error.hpp"
#include "scene/scene.hpp"

namespace armctl::cli {

inline void add_sim_scene_option(CLI::App* cmd, std::string& scene) {
  cmd->add_option("--scene", scene,
                  "A scene file (docs/scene.md): the simulated arm stops at contact with its objects, whoever "
                  "drives it (no checks of its own: the host's stall protection sees a stalled joint)");
}

// The question the simulator asks every step (arm/scene_obstacle.hpp), for arm `arm` (a name
// or an arm file) and `protocol`'s device slots. Throws ArmctlError: a bad file (the key, the
// value, what is allowed), an arm without collision shapes.
inline std::function<bool(std::span<const double>)> sim_obstacle(const std::string& arm, arm::Protocol protocol,
                                                                 const std::string& scene_file) {
  auto scene = scene::load_scene(scene_file);
  if (!scene) throw ArmctlError(scene.error());
  auto model = arm::load_arm_model(arm::arm_file_path(arm));
  if (!model) throw ArmctlError(model.error());
  auto touches = arm::scene_obstacle(*model, protocol, std::move(*scene));
  if (!touches) throw ArmctlError(touches.error());
  return std::move(*touches);
}

}  // namespace armctl::cli

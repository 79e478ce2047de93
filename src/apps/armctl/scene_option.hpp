// --scene FILE, the same in every command that plans motions (docs/scene.md): the session
// reads it before it opens the device, and every plan is checked against it.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "session/device_kinds.hpp"

namespace armctl::cli {

inline void add_scene_option(CLI::App* cmd, std::string& scene) {
  cmd->add_option("--scene", scene,
                  "A scene file (table, boxes, keep-out zones; docs/scene.md): every motion is checked "
                  "against it and the arm's own links before it starts");
}

inline session::SessionOptions with_scene(const std::string& scene, session::SessionOptions options = {}) {
  options.scene = scene;
  return options;
}

}  // namespace armctl::cli

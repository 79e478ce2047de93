// --scene FILE, the same in every command that plans motions (docs/scene.md): the session
// reads it before it opens the device, and every plan is checked against it. --fence and
// --reduced-mode switch the file's fence and reduced mode for the command.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "session/device_kinds.hpp"

namespace armctl::cli {

struct SceneArgs {
  std::string file;             // --scene FILE
  std::string fence, reduced;   // "on" | "off" | "" (as the file says)
  bool empty() const { return file.empty(); }
};

inline void add_scene_option(CLI::App* cmd, SceneArgs& scene) {
  cmd->add_option("--scene", scene.file,
                  "A scene file (table, boxes, keep-out zones, a fence, reduced mode; docs/scene.md): every motion "
                  "is checked against it and the arm's own links before it starts");
  cmd->add_option("--fence", scene.fence, "on | off: the scene file's fence (default: as the file says)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--reduced-mode", scene.reduced,
                  "on | off: the scene file's reduced mode, its tool speed cap and joint ranges (default: as the file "
                  "says)")
      ->check(CLI::IsMember({"on", "off"}));
}

inline session::SessionOptions with_scene(const SceneArgs& scene, session::SessionOptions options = {}) {
  options.scene = scene.file;
  auto on = [](const std::string& word) { return word.empty() ? std::nullopt : std::optional<bool>(word == "on"); };
  options.fence = on(scene.fence);
  options.reduced_mode = on(scene.reduced);
  return options;
}

}  // namespace armctl::cli

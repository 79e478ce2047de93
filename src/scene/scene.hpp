// What stands around the arm: a table, boxes, cylinders, capsules, spheres and keep-out zones, each
// named and placed in the arm's base frame, and parts held by the tool, which move with it.
// Read from a scene file (docs/scene.md): JSON, lengths in millimetres, angles in degrees;
// held here in SI (m, rad) like every other value of the arm layer. Pure: text in, value out.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "motion/link_bodies.hpp"
#include "scene/scene_limits.hpp"

namespace armctl::scene {

enum class ObjectRole {
  obstacle,  // something that stands there: a box, a can, a fixture
  table,     // what the arm stands on
  keep_out,  // space the arm must not enter (a person's side of the bench, a camera's view)
};
const char* to_string(ObjectRole role);  // "obstacle", "table", "keep-out zone"

struct SceneObject {
  std::string name;
  ObjectRole role = ObjectRole::obstacle;
  // Its pose: in the base frame, or in the tool frame when `attached` (a part the tool holds).
  motion::Shape shape;
  bool attached = false;
};

// How messages name an object: "the table 'table'", "box 'feeder'", "keep-out zone 'door'".
std::string describe(const SceneObject& object);

struct Scene {
  std::vector<SceneObject> objects;
  std::filesystem::path file;  // where it was read from ("" when built in code)
  // The workspace limits it sets (scene/scene_limits.hpp), each checked while it is on.
  std::optional<Fence> fence = std::nullopt;
  std::optional<ReducedMode> reduced = std::nullopt;
};

// A scene file's text; `source` names it in errors. Every error (invalid_config) names the
// key path, the value and what is allowed; nothing of a refused file is kept.
Result<Scene> parse_scene(std::string_view json_text, std::string_view source);
// Reads and parses a scene file (a regular file of at most 1 MiB).
Result<Scene> load_scene(const std::filesystem::path& file);

// Editing a scene one object at a time (the HTTP API, the ROS node): `object_json` is one
// object as a scene file writes it ({"name": ..., "box": [...], "at": [...]}), added, or
// replacing the object of its name. Errors (invalid_config: the key, the value and what is
// allowed; invalid_argument: a full scene) leave nothing changed: the result is a new value.
Result<Scene> with_object(const Scene& scene, std::string_view object_json, std::string_view source);
// The scene without the object `name`; an unknown name is invalid_argument, listing the names.
Result<Scene> without_object(const Scene& scene, std::string_view name);

// The scene with its fence / reduced mode switched on or off (Scene::fence, Scene::reduced:
// what Arm::set_fence and --fence change). Errors (invalid_argument): the scene sets none
// (given the arm file's where it sets none: arm::with_arm_limits, so the error says so).
Result<Scene> with_fence(const Scene& scene, bool on);
Result<Scene> with_reduced_mode(const Scene& scene, bool on);
// Its fence and reduced mode as a scene file writes them, {"fence": ..., "reduced": ...}
// (null where it sets none): what the apps show (armctl arm limits, GET /api/v1/scene/limits).
std::string limits_json(const Scene& scene);

// The scene as a scene file's text (millimetres, degrees): what parse_scene reads back to
// the same objects.
std::string scene_json(const Scene& scene);

}  // namespace armctl::scene

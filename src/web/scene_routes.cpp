// The planning scene over HTTP (docs/http-api.md "Scene"): read it, replace it, add or
// replace one object, remove one, save it to the scene file the server was started with.
// Every change is checked whole before it is taken (a refused one changes nothing) and is
// seen by the next plan and by the motion running now (its look-ahead, docs/scene.md).
#include <fmt/core.h>

#include "core/atomic_file.hpp"
#include "core/printable.hpp"
#include "scene/scene.hpp"
#include "web/api_error.hpp"
#include "web/server_state.hpp"

namespace armctl::web {

namespace {

arm::Arm& arm_of(WebServer::State& s) { return *s.worker.session().arm; }

json scene_answer(const scene::Scene& scene) {
  json out = json::parse(scene::scene_json(scene));
  out["file"] = scene.file.empty() ? json(nullptr) : json(scene.file.string());
  return out;
}

}  // namespace

void add_scene_routes(WebServer::State& s) {
  s.router.add("GET", "/api/v1/scene", [&s](Call& c) { c.reply(scene_answer(arm_of(s).scene())); });

  // The whole scene, as a scene file holds it.
  s.router.add("PUT", "/api/v1/scene", [&s](Call& c) {
    s.lease.require(c.client);
    if (auto ok = arm_of(s).edit_scene([&](const scene::Scene& now) -> Result<scene::Scene> {
          auto next = scene::parse_scene(c.request.body, "request body");
          if (next) next->file = now.file;  // still saved where it came from
          return next;
        });
        !ok)
      fail(ok.error());
    c.reply(scene_answer(arm_of(s).scene()));
  });

  // One object: added, or replacing the one of that name. The body is the object as a scene
  // file writes it; its "name", when given, must be the path's.
  s.router.add("PUT", "/api/v1/scene/objects/([^/]*)", [&s](Call& c) {
    s.lease.require(c.client);
    json object = c.body();
    if (!object.is_object()) throw ApiError(400, "request body: must be one scene object, e.g. {\"box\": [40, 40, 40], \"at\": [150, 0, 20]}");
    if (!object.contains("name")) object["name"] = c.params[0];
    if (object["name"] != c.params[0])
      throw ApiError(400, fmt::format("request body: name: {} differs from the object named in the path, '{}'",
                                      printable(object["name"].dump()), printable(c.params[0])));
    bool replaced = false;
    if (auto ok = arm_of(s).edit_scene([&](const scene::Scene& now) {
          for (const auto& o : now.objects) replaced = replaced || o.name == c.params[0];
          return scene::with_object(now, object.dump(), "request body");
        });
        !ok)
      fail(ok.error());
    c.reply({{"object", c.params[0]}, {"replaced", replaced}, {"scene", scene_answer(arm_of(s).scene())}});
  });

  s.router.add("DELETE", "/api/v1/scene/objects/([^/]*)", [&s](Call& c) {
    s.lease.require(c.client);
    if (auto ok = arm_of(s).edit_scene([&](const scene::Scene& now) { return scene::without_object(now, c.params[0]); }); !ok)
      throw ApiError(404, ok.error());
    c.reply({{"deleted", c.params[0]}, {"scene", scene_answer(arm_of(s).scene())}});
  });

  // The fence and reduced mode (docs/scene.md "Fence and reduced mode"): as the scene sets
  // them, each with whether it is on.
  s.router.add("GET", "/api/v1/scene/limits", [&s](Call& c) { c.reply(json::parse(scene::limits_json(arm_of(s).scene()))); });

  // Switched on or off: {"fence": true, "reduced": false}, either or both, taken together
  // or not at all.
  s.router.add("PUT", "/api/v1/scene/limits", [&s](Call& c) {
    s.lease.require(c.client);
    const json body = c.body();
    const char* wanted = "request body: must be {\"fence\": true|false, \"reduced\": true|false} (either or both)";
    if (!body.is_object() || body.empty()) throw ApiError(400, wanted);
    for (const auto& [key, value] : body.items())
      if ((key != "fence" && key != "reduced") || !value.is_boolean())
        throw ApiError(400, fmt::format("request body: {}: {}: {}", printable(key), printable(value.dump()), wanted));
    if (auto ok = arm_of(s).edit_scene([&](const scene::Scene& now) -> Result<scene::Scene> {
          Result<scene::Scene> next = now;
          if (body.contains("fence")) next = scene::with_fence(*next, body["fence"].get<bool>());
          if (next && body.contains("reduced")) next = scene::with_reduced_mode(*next, body["reduced"].get<bool>());
          return next;
        });
        !ok)
      throw ApiError(409, ok.error());
    c.reply(json::parse(scene::limits_json(arm_of(s).scene())));
  });

  // To the scene file the server was started with (--scene FILE), in one atomic replacement.
  s.router.add("POST", "/api/v1/scene/save", [&s](Call& c) {
    s.lease.require(c.client);
    const scene::Scene now = arm_of(s).scene();
    if (now.file.empty())
      throw ApiError(409, "the server was started without --scene FILE: there is no scene file to save to");
    const std::string text = scene::scene_json(now) + "\n";
    if (auto ok = write_file_atomically(now.file, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
        !ok)
      fail(ok.error());
    c.reply({{"saved", now.file.string()}, {"objects", now.objects.size()}});
  });
}

}  // namespace armctl::web

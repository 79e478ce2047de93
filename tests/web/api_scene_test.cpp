// The planning scene over HTTP (docs/http-api.md "Scene") on the embedded simulated xArm:
// objects added, replaced and removed one at a time, a whole scene put, saved to the scene
// file; a plan into an object put there is refused; bad requests change nothing.
#include <filesystem>
#include <fstream>

#include "scene/scene.hpp"
#include "api_server.hpp"

namespace armctl::web::testing {
namespace {

std::string error_of(const Reply& r) { return r.body.is_object() && r.body.contains("error") ? r.body["error"].get<std::string>() : r.text; }

TEST(WebScene, ObjectsAreAddedReplacedAndRemovedAndPlansSeeThem) {
  ApiServer api("xarm");
  api.take("page");
  Reply r = api.get("/api/v1/scene");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_TRUE(r.body["objects"].empty());
  EXPECT_TRUE(r.body["file"].is_null());

  // Before the box, the tool may go where it will stand.
  const json into_box{{"x", 150}, {"y", 0}, {"z", 40}};
  const json box{{"box", {60, 60, 80}}, {"at", {150, 0, 40}}};
  r = api.send("PUT", "/api/v1/scene/objects/crate", box.dump(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["replaced"], false);
  ASSERT_EQ(r.body["scene"]["objects"].size(), 1u);
  EXPECT_EQ(r.body["scene"]["objects"][0]["name"], "crate");
  r = api.post("/api/v1/tool", into_box, "page");
  EXPECT_EQ(r.status, 400) << r.text;
  EXPECT_NE(error_of(r).find("box 'crate'"), std::string::npos) << r.text;

  // The same name again replaces it: moved away, the move plans.
  r = api.send("PUT", "/api/v1/scene/objects/crate", json{{"name", "crate"}, {"box", {60, 60, 80}}, {"at", {-150, 0, 40}}}.dump(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["replaced"], true);
  EXPECT_EQ(api.get("/api/v1/scene").body["objects"].size(), 1u);

  // Refused, nothing changed: a bad shape (the key named), a name that is not the path's, a
  // body that is no object, a client without control.
  r = api.send("PUT", "/api/v1/scene/objects/ball", json{{"sphere", {{"radius", -5}}}, {"at", {0, 0, 0}}}.dump(), "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error_of(r).find("sphere.radius"), std::string::npos) << r.text;
  r = api.send("PUT", "/api/v1/scene/objects/ball", json{{"name", "other"}, {"sphere", {{"radius", 5}}}, {"at", {0, 0, 0}}}.dump(), "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error_of(r).find("differs from the object named in the path"), std::string::npos) << r.text;
  EXPECT_EQ(api.send("PUT", "/api/v1/scene/objects/ball", "[1, 2]", "page").status, 400);
  EXPECT_EQ(api.send("PUT", "/api/v1/scene/objects/ball", box.dump(), "watcher").status, 409);
  EXPECT_EQ(api.get("/api/v1/scene").body["objects"].size(), 1u);

  // Removed: unknown names are 404 listing what there is.
  r = api.send("DELETE", "/api/v1/scene/objects/nothere", "", "page");
  EXPECT_EQ(r.status, 404);
  EXPECT_NE(error_of(r).find("the scene holds: crate"), std::string::npos) << r.text;
  r = api.send("DELETE", "/api/v1/scene/objects/crate", "", "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_TRUE(api.get("/api/v1/scene").body["objects"].empty());

  // A whole scene; a bad one (the key and value named) leaves the last one.
  r = api.send("PUT", "/api/v1/scene", R"({"objects": [{"name": "desk", "table": {"top": 0}}, {"name": "crate", "box": [60, 60, 80], "at": [150, 0, 40]}]})", "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["objects"].size(), 2u);
  r = api.send("PUT", "/api/v1/scene", R"({"objects": [{"name": "crate", "box": [60, 60], "at": [150, 0, 40]}]})", "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error_of(r).find("objects[0].box"), std::string::npos) << r.text;
  EXPECT_EQ(api.get("/api/v1/scene").body["objects"].size(), 2u);
  EXPECT_EQ(api.post("/api/v1/tool", into_box, "page").status, 400);

  // Nothing to save to without --scene FILE.
  r = api.post("/api/v1/scene/save", json::object(), "page");
  EXPECT_EQ(r.status, 409);
  EXPECT_NE(error_of(r).find("--scene FILE"), std::string::npos) << r.text;
}

TEST(WebScene, SavesToTheSceneFileItWasStartedWith) {
  const auto dir = std::filesystem::temp_directory_path() / ("armctl-web-scene-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto file = dir / "desk.json";
  std::ofstream(file) << R"({"objects": [{"name": "desk", "table": {"top": 0}}]})";
  {
    ApiServer api("xarm", {}, "", file);
    api.take("page");
    Reply r = api.get("/api/v1/scene");
    EXPECT_EQ(r.body["file"], file.string());
    ASSERT_EQ(r.body["objects"].size(), 1u);
    ASSERT_EQ(api.send("PUT", "/api/v1/scene/objects/can", json{{"cylinder", {{"radius", 30}, {"length", 120}}}, {"at", {0, 200, 60}}}.dump(), "page").status, 200);
    r = api.post("/api/v1/scene/save", json::object(), "page");
    ASSERT_EQ(r.status, 200) << r.text;
    EXPECT_EQ(r.body["objects"], 2);
  }
  // The file reads back with both, as the next server (or `armctl arm --scene`) takes it.
  const auto saved = scene::load_scene(file);
  ASSERT_TRUE(saved) << saved.error().message;
  ASSERT_EQ(saved->objects.size(), 2u);
  EXPECT_EQ(saved->objects[1].name, "can");
  EXPECT_NEAR(saved->objects[1].shape.pose.translation().y(), 0.2, 1e-9);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace armctl::web::testing

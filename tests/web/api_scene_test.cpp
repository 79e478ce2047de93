// The planning scene over HTTP (docs/http-api.md "Scene") on the embedded simulated xArm:
// objects added, replaced and removed one at a time, a whole scene put, saved to the scene
// file; a plan into an object put there is refused; bad requests change nothing.
#include <cmath>
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

// The xArm's desk scene (examples/scenes/xarm-desk.json): a box to the right front.
const char* kDesk = R"({"objects": [{"name": "desk", "table": {"top": 0, "size": [800, 600], "center": [150, 0]}},
                                    {"name": "box", "box": [50, 50, 80], "at": [150, -100, 40]}]})";

// The motion ends with the tool behind the desk's box (150, -190, 40 mm), no error.
void expect_behind_the_box(ApiServer& api) {
  ASSERT_TRUE(api.wait_idle(60s));
  const json state = api.get("/api/v1/state").body;
  EXPECT_EQ(state["last_error"], "") << state;
  EXPECT_NEAR(state["tool"]["x"].get<double>(), 150, 1) << state;
  EXPECT_NEAR(state["tool"]["y"].get<double>(), -190, 1) << state;
  EXPECT_NEAR(state["tool"]["z"].get<double>(), 40, 1) << state;
}

// A refused move answers with the collision's detail (which two bodies, where), so that a
// page draws them without reading the message; "avoid": true goes around the same box, as
// `armctl arm move-to --avoid` does, and the arm arrives (the simulator, which knows the
// scene too, would have stalled it at a contact).
TEST(WebScene, AMoveIntoTheBoxIsRefusedWithItsBodiesAndGoesAroundWithAvoid) {
  ApiServer api("xarm");
  api.take("page");
  api.first_positions();
  ASSERT_EQ(api.send("PUT", "/api/v1/scene", kDesk, "page").status, 200);
  const json behind{{"x", 150}, {"y", -190}, {"z", 40}};
  Reply r = api.post("/api/v1/tool", behind, "page");
  ASSERT_EQ(r.status, 400) << r.text;
  ASSERT_TRUE(r.body.contains("collision")) << r.text;
  const json& c = r.body["collision"];
  ASSERT_EQ(c["bodies"].size(), 2u);
  bool box = false, link = false;
  for (const json& b : c["bodies"]) {
    box = box || (b["kind"] == "object" && b["name"] == "box" && b["text"] == "box 'box'");
    link = link || (b["kind"] == "link" && b["name"].is_string() && error_of(r).find(b["text"].get<std::string>()) != std::string::npos);
  }
  EXPECT_TRUE(box) << c;
  EXPECT_TRUE(link) << c;
  // Where they touch: at the box (its faces are 25 mm from its centre, a few mm of depth).
  ASSERT_EQ(c["point"].size(), 3u);
  EXPECT_NEAR(c["point"][0].get<double>(), 150, 40) << c;
  EXPECT_NEAR(c["point"][1].get<double>(), -100, 40) << c;
  EXPECT_GT(c["depth_mm"].get<double>(), 0) << c;
  EXPECT_GT(c["fraction"].get<double>(), 0) << c;
  EXPECT_TRUE(c["line"].is_null());
  EXPECT_EQ(c["while_moving"], false);
  // Where the arm would be then, every joint in deg: not where it stands (all at 0).
  ASSERT_EQ(c["joints"].size(), 6u) << c;
  EXPECT_GT(std::abs(c["joints"]["servo6"].get<double>()), 10) << c;
  EXPECT_TRUE(api.wait_idle());
  const auto before = api.get("/api/v1/state").body["tool"];

  // Bad avoid requests: nothing moves.
  json bad = behind;
  bad["avoid"] = true;
  bad["linear"] = true;
  r = api.post("/api/v1/tool", bad, "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error_of(r).find("a straight line has no detour"), std::string::npos) << r.text;
  bad = behind;
  bad["avoid_time"] = 2;
  r = api.post("/api/v1/tool", bad, "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error_of(r).find("avoid_time: is allowed only with \"avoid\": true"), std::string::npos) << r.text;
  bad["avoid"] = true;
  bad["avoid_time"] = 120;
  r = api.post("/api/v1/tool", bad, "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error_of(r).find("0.01..60"), std::string::npos) << r.text;
  EXPECT_EQ(api.get("/api/v1/state").body["tool"], before);

  json around = behind;
  around["avoid"] = true;
  around["avoid_time"] = 5;
  r = api.post("/api/v1/tool", around, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_GE(r.body["avoided"]["waypoints"].get<int>(), 1) << r.text;
  EXPECT_GT(r.body["avoided"]["planning_s"].get<double>(), 0) << r.text;
  expect_behind_the_box(api);
}

// A program whose PTP goes through the box: the check and the run are refused naming the line
// and the box; with "avoid": true both go around it, and the arm arrives behind it.
TEST(WebScene, AProgramGoesAroundTheBoxWithAvoid) {
  ApiServer api("xarm");
  api.take("page");
  api.first_positions();
  ASSERT_EQ(api.send("PUT", "/api/v1/scene", kDesk, "page").status, 200);
  const json program{{"source", "wait 0.1s\nptp pose(x=150mm, y=-190mm, z=40mm)\n"}};
  Reply r = api.post("/api/v1/program/check", program, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["ok"], false) << r.text;
  ASSERT_EQ(r.body["errors"].size(), 1u) << r.text;
  EXPECT_EQ(r.body["errors"][0]["line"], 2) << r.text;
  EXPECT_NE(r.body["errors"][0]["message"].get<std::string>().find("box 'box'"), std::string::npos) << r.text;
  // The line's collision, for the page to draw: the box and the line.
  const json collision = r.body["errors"][0]["collision"];
  const json box{{"kind", "object"}, {"name", "box"}, {"text", "box 'box'"}};
  EXPECT_TRUE(collision["bodies"][0] == box || collision["bodies"][1] == box) << r.text;
  EXPECT_EQ(collision["line"], 2) << r.text;
  EXPECT_EQ(collision["while_moving"], false) << r.text;
  // A run refused the same way carries it too, and so does the live state.
  r = api.post("/api/v1/program/run", program, "page");
  ASSERT_EQ(r.status, 400) << r.text;
  EXPECT_EQ(r.body["errors"][0]["collision"]["bodies"], collision["bodies"]) << r.text;
  EXPECT_EQ(api.get("/api/v1/state", "page").body["last_collision"]["bodies"], collision["bodies"]);
  json bad = program;
  bad["avoid_time"] = 2;
  EXPECT_EQ(api.post("/api/v1/program/check", bad, "page").status, 400);
  json around = program;
  around["avoid"] = true;
  around["avoid_time"] = 5;
  r = api.post("/api/v1/program/check", around, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["ok"], true) << r.text;
  r = api.post("/api/v1/program/run", around, "page");
  ASSERT_EQ(r.status, 202) << r.text;
  expect_behind_the_box(api);
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

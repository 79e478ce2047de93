// The fence and reduced mode over HTTP (docs/http-api.md "Fence and reduced mode") on both
// embedded simulators: a server started with a scene file that sets them shows them in
// GET /api/v1/scene/limits and in the state; a move out of the fence is refused before
// anything moves and runs once the fence is switched off; reduced mode switched on refuses a
// joint move beyond its range; switching needs control, and a bad body or a limit the scene
// does not set changes nothing.
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <fmt/core.h>

#include "api_server.hpp"

namespace armctl::web::testing {
namespace {

using namespace std::chrono_literals;

std::string error_of(const Reply& r) {
  return r.body.is_object() && r.body.contains("error") ? r.body["error"].get<std::string>() : r.text;
}

// A scene file with a fence that keeps the tool at y up to `y_max` mm, and a reduced mode
// (off) that narrows `joint` to -20..20.
std::filesystem::path scene_file(const std::string& arm, double y_max, const std::string& joint) {
  const auto path = std::filesystem::temp_directory_path() / fmt::format("armctl-web-fence-{}-{}.json", arm, ::getpid());
  std::ofstream(path) << fmt::format(R"({{"fence": {{"min": [-800, -800, -100], "max": [800, {}, 800]}},
      "reduced": {{"joints": {{"{}": [-20, 20]}}, "on": false}}}})",
                                     y_max, joint);
  return path;
}

json positions(const ApiServer& api) {
  json out = json::array();
  const Reply state = api.get("/api/v1/state", "page");
  for (const auto& j : state.body["joints"]) out.push_back(j["position"]);
  return out;
}

struct ArmCase {
  std::string arm, joint;
  double y_max;   // the fence's y (mm), the arm's start inside it
  json target;    // a tool target (mm) beyond it
};

void fence_and_reduced_mode(const ArmCase& c) {
  const auto file = scene_file(c.arm, c.y_max, c.joint);
  ApiServer api(c.arm, {}, "", file);
  api.take("page");
  Reply r = api.get("/api/v1/scene/limits");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["fence"]["on"], true);
  EXPECT_EQ(r.body["fence"]["max"][1], c.y_max);
  EXPECT_EQ(r.body["reduced"]["on"], false);
  EXPECT_EQ(api.get("/api/v1/state", "page").body["limits"], (json{{"fence", true}, {"reduced", false}}));

  // Out of the fence: refused, naming it, and nothing moved.
  const json before = positions(api);
  r = api.post("/api/v1/tool", c.target, "page");
  EXPECT_EQ(r.status, 400) << r.text;
  EXPECT_NE(error_of(r).find("would leave the fence"), std::string::npos) << r.text;
  EXPECT_EQ(positions(api), before);
  // The live state carries it too, for a page that did not send the move.
  json last = api.get("/api/v1/state", "page").body["last_collision"];
  EXPECT_EQ(last["limit"], "fence") << last;
  EXPECT_EQ(last["while_moving"], false) << last;

  // Switching needs control; a bad body and a limit the scene does not set change nothing.
  EXPECT_EQ(api.send("PUT", "/api/v1/scene/limits", R"({"fence": false})", "watcher").status, 409);
  r = api.send("PUT", "/api/v1/scene/limits", R"({"fence": "off"})", "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error_of(r).find("request body: fence: \"off\""), std::string::npos) << r.text;
  EXPECT_EQ(api.send("PUT", "/api/v1/scene/limits", R"({"walls": true})", "page").status, 400);
  EXPECT_EQ(api.get("/api/v1/scene/limits").body["fence"]["on"], true);

  // Off: the same move plans and runs; reduced mode on: a joint move beyond its range is refused.
  r = api.send("PUT", "/api/v1/scene/limits", R"({"fence": false, "reduced": true})", "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["fence"]["on"], false);
  EXPECT_EQ(r.body["reduced"]["on"], true);
  EXPECT_EQ(api.get("/api/v1/state", "page").body["limits"], (json{{"fence", false}, {"reduced", true}}));
  r = api.post("/api/v1/joints", json{{"positions", {{c.joint, 30}}}}, "page");
  EXPECT_EQ(r.status, 400) << r.text;
  EXPECT_NE(error_of(r).find("reduced range"), std::string::npos) << r.text;
  r = api.send("PUT", "/api/v1/scene/limits", R"({"reduced": false})", "page");
  ASSERT_EQ(r.status, 200) << r.text;
  r = api.post("/api/v1/tool", c.target, "page");
  EXPECT_EQ(r.status, 200) << r.text;
  ASSERT_TRUE(api.wait_idle(30s));
  EXPECT_TRUE(api.get("/api/v1/state", "page").body["last_collision"].is_null());  // a success clears it

  // The fence switched on while the arm moves back out of it: the look-ahead stops the arm
  // before it leaves, and the state says where, while moving.
  r = api.post("/api/v1/tool", json{{"x", c.target["x"]}, {"y", -c.target["y"].get<double>()}, {"z", c.target["z"]}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  ASSERT_TRUE(api.wait_idle(30s));
  r = api.post("/api/v1/tool", c.target, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  ASSERT_EQ(api.send("PUT", "/api/v1/scene/limits", R"({"fence": true})", "page").status, 200);
  ASSERT_TRUE(api.wait_idle(30s));
  const json state = api.get("/api/v1/state", "page").body;
  EXPECT_NE(state["last_error"].get<std::string>().find("fence"), std::string::npos) << state;
  last = state["last_collision"];
  EXPECT_EQ(last["limit"], "fence") << state;
  EXPECT_EQ(last["while_moving"], true) << state;
  EXPECT_LE(state["tool"]["y"].get<double>(), c.y_max) << state;
  std::filesystem::remove(file);
}

TEST(WebFence, XarmFenceAndReducedMode) {
  fence_and_reduced_mode({"xarm", "servo5", 100, json{{"x", 150}, {"y", 150}, {"z", 200}}});
}

TEST(WebFence, ScaraFenceAndReducedMode) {
  fence_and_reduced_mode({"scara", "SHOULDER", 200, json{{"x", 400}, {"y", 400}, {"z", 250}}});
}

TEST(WebFence, ALimitTheSceneDoesNotSetIsRefused) {
  ApiServer api("xarm");
  api.take("page");
  Reply r = api.get("/api/v1/scene/limits");
  EXPECT_TRUE(r.body["fence"].is_null());
  EXPECT_TRUE(api.get("/api/v1/state", "page").body["limits"]["fence"].is_null());
  r = api.send("PUT", "/api/v1/scene/limits", R"({"fence": true})", "page");
  EXPECT_EQ(r.status, 409);
  EXPECT_NE(error_of(r).find("the scene sets no fence, nor does the arm file"), std::string::npos) << r.text;
}

}  // namespace
}  // namespace armctl::web::testing

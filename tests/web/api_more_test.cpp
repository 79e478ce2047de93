// The API's points, action groups and programs on the embedded simulators.
#include <filesystem>
#include <set>
#include <utility>

#include "files/points_file.hpp"
#include "api_server.hpp"

namespace armctl::web::testing {
namespace {

std::filesystem::path temp_dir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::temp_directory_path() /
             ("armctl-web-" + std::string(info->name()) + "-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(WebPoints, RecordListDeleteAndSave) {
  const auto file = temp_dir("points") / "taught.points";
  ServerOptions o;
  o.points_file = file;
  ApiServer api("xarm", o);
  const auto here = api.first_positions();
  api.take("page");
  Reply r = api.post("/api/v1/points", {{"name", "pick"}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["replaced"], false);
  r = api.get("/api/v1/points");
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.body["file"], file.string());
  ASSERT_EQ(r.body["points"].size(), 1u);
  const json& p = r.body["points"][0];
  EXPECT_EQ(p["name"], "pick");
  const auto& model = api.worker().model();
  for (std::size_t i = 0; i < model.joints.size(); ++i)
    EXPECT_NEAR(p["joints"][model.joints[i].name].get<double>(), here.positions[i] * 180 / M_PI, 0.5);
  EXPECT_NEAR(p["tool"]["z"].get<double>(), here.pose->position.z() * 1e3, 1.0);
  // The file holds it, in the program points-file format.
  const auto saved = files::read_points_file(file);
  ASSERT_TRUE(saved) << saved.error().message;
  ASSERT_EQ(saved->points.size(), 1u);
  EXPECT_EQ(saved->points[0].name, "pick");
  // Same name again replaces it.
  EXPECT_EQ(api.post("/api/v1/points", {{"name", "pick"}}, "page").body["replaced"], true);
  EXPECT_EQ(api.get("/api/v1/points").body["points"].size(), 1u);
  // Bad names.
  r = api.post("/api/v1/points", {{"name", "ptp"}}, "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body["error"].get<std::string>().find("word of the program language"), std::string::npos);
  EXPECT_EQ(api.post("/api/v1/points", {{"name", "9lives"}}, "page").status, 400);
  EXPECT_EQ(api.post("/api/v1/points", {{"name", 3}}, "page").status, 400);
  // Delete.
  EXPECT_EQ(api.send("DELETE", "/api/v1/points/nothere", "", "page").status, 404);
  EXPECT_EQ(api.send("DELETE", "/api/v1/points/pick", "", "watcher").status, 409);
  r = api.send("DELETE", "/api/v1/points/pick", "", "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_TRUE(api.get("/api/v1/points").body["points"].empty());
  EXPECT_TRUE(files::read_points_file(file)->points.empty());
  // A server started on the file lists what it holds.
  ASSERT_EQ(api.post("/api/v1/points", {{"name", "home"}}, "page").status, 200);
  ApiServer again("xarm", o);
  EXPECT_EQ(again.get("/api/v1/points").body["points"][0]["name"], "home");
}

json frames_at(const arm::ArmModel& model, std::initializer_list<double> values) {
  json frames = json::array();
  for (double v : values) {
    json positions = json::object();
    for (const auto& j : model.joints) positions[j.name] = j.role == arm::JointRole::gripper ? 0.0 : v;
    frames.push_back({{"time_ms", 400}, {"positions", positions}});
  }
  return frames;
}

TEST(WebGroups, DownloadRunAndReadBack) {
  ApiServer api("xarm");
  api.first_positions();
  api.take("page");
  const auto& model = api.worker().model();
  const json frames = frames_at(model, {10.0, -15.0});
  Reply r = api.send("PUT", "/api/v1/groups/3", json{{"frames", frames}}.dump(), "page");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["frames"], 2);
  r = api.post("/api/v1/groups/speed", {{"percent", 200}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  r = api.post("/api/v1/groups/3/run", {{"count", 1}}, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  // The board plays it: the arm ends at the last frame.
  EXPECT_TRUE(api.wait_until([&](const session::ArmSnapshot& s) {
    for (std::size_t i = 0; i < model.joints.size(); ++i)
      if (model.joints[i].role != arm::JointRole::gripper && std::abs(s.positions[i] * 180 / M_PI + 15.0) > 0.5)
        return false;
    return true;
  }));
  r = api.get("/api/v1/frame");
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.body["time_ms"], 1000);
  EXPECT_NEAR(r.body["positions"][model.joints[0].name].get<double>(), -15.0, 0.5);
  EXPECT_EQ(api.post("/api/v1/groups/3/run", {{"continuous", true}}, "page").status, 200);
  EXPECT_EQ(api.post("/api/v1/groups/stop", json::object(), "page").status, 200);
  EXPECT_EQ(api.send("DELETE", "/api/v1/groups/3", "", "page").status, 200);
  // Erased: the board ignores a run of it, and the page is told so.
  r = api.post("/api/v1/groups/3/run", {{"count", 1}}, "page");
  EXPECT_EQ(r.status, 409) << r.text;
  EXPECT_NE(r.text.find("group 3 did not start"), std::string::npos) << r.text;
}

TEST(WebGroups, BadGroupRequestsSendNothing) {
  ApiServer api("xarm");
  const auto before = api.first_positions();
  api.take("page");
  const auto& model = api.worker().model();
  auto error = [&](const Reply& r) { return r.body.is_object() ? r.body["error"].get<std::string>() : r.text; };
  json frames = frames_at(model, {10.0, 500.0});
  Reply r = api.send("PUT", "/api/v1/groups/3", json{{"frames", frames}}.dump(), "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error(r).find("frames[1]"), std::string::npos) << error(r);
  frames = frames_at(model, {10.0});
  frames[0]["time_ms"] = 30001;
  r = api.send("PUT", "/api/v1/groups/3", json{{"frames", frames}}.dump(), "page");
  EXPECT_NE(error(r).find("frames[0].time_ms: 30001 is not allowed"), std::string::npos) << error(r);
  r = api.send("PUT", "/api/v1/groups/255", json{{"frames", frames_at(model, {1.0})}}.dump(), "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(error(r).find("group '255' is not allowed; a group number 0..254"), std::string::npos) << error(r);
  r = api.post("/api/v1/groups/3/run", {{"count", 70000}}, "page");
  EXPECT_NE(error(r).find("count: 70000 is not allowed; a whole number 1..65535"), std::string::npos) << error(r);
  r = api.post("/api/v1/groups/speed", {{"percent", 1001}}, "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(api.post("/api/v1/groups/import", {{"format", "xls"}, {"content", ""}}).status, 400);
  EXPECT_FALSE(api.worker().busy());
  EXPECT_EQ(api.worker().snapshot().device, before.device);
}

TEST(WebGroups, ImportExportRoundTrip) {
  ApiServer api("xarm");
  const auto& model = api.worker().model();
  const json frames = frames_at(model, {0.0, 24.0});
  for (const char* format : {"group", "rob"}) {
    const Reply e = api.post("/api/v1/groups/export", {{"format", format}, {"frames", frames}});
    ASSERT_EQ(e.status, 200) << e.text;
    const Reply i = api.post("/api/v1/groups/import", {{"format", format}, {"content", e.body["content"]}});
    ASSERT_EQ(i.status, 200) << i.text;
    ASSERT_EQ(i.body["frames"].size(), 2u);
    EXPECT_EQ(i.body["frames"][1]["time_ms"], 400);
    EXPECT_NEAR(i.body["frames"][1]["positions"][model.joints[0].name].get<double>(), 24.0, 0.13) << format;
  }
}

const char* kPoints = "home joints=0deg,20deg,40deg,40deg,0deg\n";

TEST(WebProgram, CheckPlacesErrorsAtTheirLine) {
  ApiServer api("xarm");
  api.first_positions();
  Reply r = api.post("/api/v1/program/check", {{"source", "ptp home speed=40%\nwait 0.1s\n"}, {"points", kPoints}});
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["ok"], true);
  EXPECT_TRUE(r.body["errors"].empty());
  EXPECT_GT(r.body["duration_s"].get<double>(), 0.1);
  r = api.post("/api/v1/program/check", {{"source", "ptp home\nwait 0.1s\nptp nowhere\n"}, {"points", kPoints}});
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["ok"], false);
  ASSERT_EQ(r.body["errors"].size(), 1u);
  EXPECT_EQ(r.body["errors"][0]["line"], 3);
  EXPECT_EQ(r.body["errors"][0]["column"], 5);
  EXPECT_NE(r.body["errors"][0]["message"].get<std::string>().find("nowhere"), std::string::npos);
  // Unreachable: the planner's error, at its line.
  r = api.post("/api/v1/program/check", {{"source", "wait 0.1s\nptp far\n"}, {"points", "far x=900mm y=0mm z=50mm\n"}});
  EXPECT_EQ(r.body["ok"], false);
  EXPECT_EQ(r.body["errors"][0]["line"], 2) << r.text;
  EXPECT_EQ(api.post("/api/v1/program/check", {{"points", kPoints}}).status, 400);  // no source
}

// A sum of 250,000 terms (and 250,000 nested signs) sent to the check endpoint crashed
// `armctl serve` (stack overflow): now an error at its place, and the server answers on.
TEST(WebProgram, CheckSurvivesLongAndDeepExpressions) {
  ApiServer api("xarm");
  api.first_positions();
  std::string sum = "n = 1";
  for (int i = 0; i < 250'000; ++i) sum += "+1";
  for (const std::string& source : {sum + "\n", "n = " + std::string(250'000, '-') + "1\n"}) {
    const Reply r = api.post("/api/v1/program/check", {{"source", source}, {"points", kPoints}});
    ASSERT_EQ(r.status, 200) << r.text.substr(0, 200);
    EXPECT_EQ(r.body["ok"], false);
    ASSERT_EQ(r.body["errors"].size(), 1u);
    EXPECT_EQ(r.body["errors"][0]["line"], 1);
    const std::string message = r.body["errors"][0]["message"];
    EXPECT_TRUE(message.find("at most 1000 operators in one expression") != std::string::npos ||
                message.find("at most 64 parentheses, signs and NOTs") != std::string::npos)
        << message;
  }
  const Reply again = api.post("/api/v1/program/check", {{"source", "wait 0.1s\n"}, {"points", kPoints}});
  EXPECT_EQ(again.status, 200);
  EXPECT_EQ(again.body["ok"], true);
}

TEST(WebProgram, RunShowsProgressAndEnds) {
  ApiServer api("xarm");
  api.first_positions();
  api.take("page");
  Reply r = api.post("/api/v1/program/pause", json::object(), "page");
  EXPECT_EQ(r.status, 409);
  const std::string source = "  ptp home speed=30%\nprint \"at home\"\nwait 0.2s\n";
  r = api.post("/api/v1/program/run", {{"source", source}, {"points", kPoints}, {"speed", 1.0}}, "page");
  ASSERT_EQ(r.status, 202) << r.text;
  EXPECT_EQ(r.body["started"], true);
  // While it runs the state shows it, then it ends idle with its print.
  bool saw_running = false;
  std::set<std::pair<int, int>> places;  // (line, column) while running
  ASSERT_TRUE(api.wait_until([&](const session::ArmSnapshot&) {
    const json p = api.get("/api/v1/state", "page").body["program"];
    if (p.is_object() && p["state"] == "running") {
      saw_running = true;
      places.insert({p["line"].get<int>(), p["column"].get<int>()});
    }
    return p.is_object() && p["state"] == "idle" && !api.worker().busy();
  }));
  EXPECT_TRUE(saw_running);
  EXPECT_TRUE(places.count({1, 3})) << "the indented ptp runs at line 1, column 3";
  const json p = api.get("/api/v1/state", "page").body["program"];
  ASSERT_EQ(p["prints"].size(), 1u);
  EXPECT_EQ(p["prints"][0], "at home");
  const auto s = api.worker().snapshot();
  EXPECT_TRUE(s.last_error.empty()) << s.last_error;
  EXPECT_NEAR(s.positions[1] * 180 / M_PI, 20.0, 0.5);
  // A program with an error is refused with the error at its line, and nothing runs.
  r = api.post("/api/v1/program/run", {{"source", "wait 0.1s\nptp nowhere\n"}, {"points", kPoints}}, "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(r.body["errors"][0]["line"], 2) << r.text;
  r = api.post("/api/v1/program/run", {{"source", "ptp home"}, {"points", kPoints}, {"speed", 0}}, "page");
  EXPECT_EQ(r.status, 400);
  EXPECT_FALSE(api.worker().busy());
}

TEST(WebProgram, PauseResumeAndStop) {
  ApiServer api("xarm");
  const auto before = api.first_positions();
  api.take("page");
  const std::string source = "ptp home speed=10%\nptp joints(0deg,0deg,0deg,0deg,0deg) speed=10%\n";
  Reply r = api.post("/api/v1/program/run", {{"source", source}, {"points", kPoints}}, "page");
  ASSERT_EQ(r.status, 202) << r.text;
  ASSERT_TRUE(api.wait_until([&](const session::ArmSnapshot& s) { return s.progress && s.progress->t > 0.2; }));
  ASSERT_EQ(api.post("/api/v1/program/pause", json::object(), "page").status, 200);
  EXPECT_EQ(api.get("/api/v1/state", "page").body["program"]["state"], "paused");
  ASSERT_TRUE(api.wait_until([&](const session::ArmSnapshot& s) { return s.progress && s.progress->paused; }));
  ASSERT_EQ(api.post("/api/v1/program/resume", json::object(), "page").status, 200);
  ASSERT_TRUE(api.wait_until([&](const session::ArmSnapshot& s) { return s.progress && !s.progress->paused; }));
  ASSERT_EQ(api.post("/api/v1/program/stop", json::object(), "page").status, 200);
  ASSERT_TRUE(api.wait_idle());
  EXPECT_EQ(api.get("/api/v1/state", "page").body["program"]["state"], "idle");
  (void)before;
}

}  // namespace
}  // namespace armctl::web::testing

// The HTTP API on loopback (docs/http-api.md): model, URDF, state, events, static files,
// routing errors, the security checks and the control lease.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <condition_variable>
#include <fstream>
#include <sstream>
#include <thread>

#include "api_server.hpp"

namespace armctl::web::testing {
namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(WebApi, ModelOfTheXarm) {
  ApiServer api("xarm");
  const Reply r = api.get("/api/v1/model");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["arm"], "xarm");
  EXPECT_EQ(r.body["protocol"], "robot_commands");
  EXPECT_EQ(r.body["groups_supported"], true);
  EXPECT_EQ(r.body["has_gripper"], true);
  const auto& model = api.worker().model();
  ASSERT_EQ(r.body["joints"].size(), model.joints.size());
  for (std::size_t i = 0; i < model.joints.size(); ++i) {
    const auto& j = r.body["joints"][i];
    EXPECT_EQ(j["name"], model.joints[i].name);
    EXPECT_EQ(j["kind"], "revolute");
    EXPECT_EQ(j["unit"], "deg");
    EXPECT_EQ(j["raw_unit"], "servo units");
    EXPECT_NEAR(j["min"].get<double>(), model.joints[i].limits.lower * 180 / M_PI, 1e-9);
    EXPECT_LT(j["min"].get<double>(), j["max"].get<double>());
    EXPECT_GE(j["raw_min"].get<double>(), 0);
    EXPECT_LE(j["raw_max"].get<double>(), 1000);
  }
}

TEST(WebApi, ModelOfTheScaraOnTheJointBus) {
  ApiServer api("scara");
  const Reply r = api.get("/api/v1/model");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["protocol"], "joint_bus");
  EXPECT_EQ(r.body["groups_supported"], false);
  bool prismatic = false;
  for (const auto& j : r.body["joints"])
    if (j["kind"] == "prismatic") {
      prismatic = true;
      EXPECT_EQ(j["unit"], "mm");
      EXPECT_EQ(j["raw_unit"], "counts");
    }
  EXPECT_TRUE(prismatic);
  // No action groups over the joint bus.
  const Reply g = api.send("PUT", "/api/v1/groups/1", R"({"frames":[]})", "page");
  EXPECT_EQ(g.status, 409);
  EXPECT_NE(g.body["error"].get<std::string>().find("action groups need a Robot Commands board"), std::string::npos);
}

TEST(WebApi, UrdfAndState) {
  ApiServer api("xarm");
  const Reply u = api.get("/api/v1/urdf");
  ASSERT_EQ(u.status, 200);
  EXPECT_EQ(u.content_type, "application/xml");
  EXPECT_EQ(u.text, file_text(api.worker().model().urdf.string()));
  // The battery is read after the first positions: wait for both.
  ASSERT_TRUE(api.wait_until([](const session::ArmSnapshot& s) { return !s.positions.empty() && s.status.battery_volts; }));
  const Reply s = api.get("/api/v1/state", "page");
  ASSERT_EQ(s.status, 200) << s.text;
  EXPECT_GT(s.body["sequence"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(s.body["link"]["ok"], true);
  ASSERT_EQ(s.body["joints"].size(), api.worker().model().joints.size());
  const auto snapshot = api.worker().snapshot();
  for (std::size_t i = 0; i < snapshot.positions.size(); ++i) {
    const auto& j = s.body["joints"][i];
    EXPECT_EQ(j["name"], api.worker().model().joints[i].name);
    EXPECT_TRUE(j["position"].is_number());
    EXPECT_TRUE(j["raw"].is_number());
  }
  EXPECT_TRUE(s.body["tool"]["z"].is_number());
  EXPECT_TRUE(s.body["battery_volts"].is_number());
  EXPECT_EQ(s.body["control"]["you"], false);
  EXPECT_EQ(s.body["control"]["holder"], false);
  EXPECT_TRUE(s.body["motion"].is_null());
  EXPECT_TRUE(s.body["program"].is_null());
}

TEST(WebApi, StaticFilesAreTheEmbeddedOnes) {
  ApiServer api;
  const std::string index = file_text(std::string(ARMCTL_SOURCE_DIR) + "/web/public/index.html");
  for (const char* path : {"/", "/index.html"}) {
    const Reply r = api.get(path);
    ASSERT_EQ(r.status, 200) << path;
    // As embedded, but for the nonce on its boot script (api_limits_test.cpp checks it).
    std::string served = r.text;
    const auto nonce = served.find("<script nonce=\"");
    ASSERT_NE(nonce, std::string::npos);
    served.erase(nonce + 7, served.find('>', nonce) - nonce - 7);
    EXPECT_EQ(served, index);
    EXPECT_EQ(r.content_type, "text/html; charset=utf-8");
    EXPECT_EQ(r.headers.find("Cache-Control")->second, "no-cache");
  }
  const Reply missing = api.get("/assets/nothing.js");
  EXPECT_EQ(missing.status, 404);
  EXPECT_NE(missing.body["error"].get<std::string>().find("no such path: /assets/nothing.js"), std::string::npos);
  EXPECT_EQ(api.send("POST", "/index.html", "{}").status, 405);
}

TEST(WebApi, UnknownPathsAndMethods) {
  ApiServer api;
  const Reply r = api.get("/api/v1/nothing");
  EXPECT_EQ(r.status, 404);
  EXPECT_TRUE(r.body.contains("error"));
  const Reply m = api.get("/api/v1/joints");
  EXPECT_EQ(m.status, 405);
  EXPECT_EQ(m.headers.find("Allow")->second, "POST");
  EXPECT_NE(m.body["error"].get<std::string>().find("GET is not allowed on /api/v1/joints; allowed: POST"),
            std::string::npos);
  EXPECT_EQ(api.send("DELETE", "/api/v1/state", "").status, 405);
}

TEST(WebApi, HostAndOriginChecks) {
  ApiServer api;
  const std::string port = std::to_string(api.port());
  EXPECT_EQ(api.get("/api/v1/model", "", {{"Host", "localhost:" + port}}).status, 200);
  const Reply rebound = api.get("/api/v1/model", "", {{"Host", "evil.example:" + port}});
  EXPECT_EQ(rebound.status, 403);
  EXPECT_NE(rebound.body["error"].get<std::string>().find("is not this server"), std::string::npos);
  EXPECT_EQ(api.get("/", "", {{"Host", "evil.example:" + port}}).status, 403);  // static files too
  EXPECT_EQ(api.get("/api/v1/model", "", {{"Origin", "http://127.0.0.1:" + port}}).status, 200);
  const Reply cross = api.get("/api/v1/model", "", {{"Origin", "http://evil.example"}});
  EXPECT_EQ(cross.status, 403);
  EXPECT_NE(cross.body["error"].get<std::string>().find("Origin 'http://evil.example' is not allowed"),
            std::string::npos);
}

TEST(WebApi, RefusalsMoveNothing) {
  ApiServer api;
  const auto before = api.first_positions();
  api.take("page");
  const std::string port = std::to_string(api.port());
  const std::string name = api.worker().model().joints[0].name;
  const std::string move = json{{"positions", {{name, 20}}}}.dump();
  // A form post from another site: other origin, and not JSON.
  EXPECT_EQ(api.send("POST", "/api/v1/joints", move, "page", {{"Origin", "http://evil.example"}}).status, 403);
  const Reply form = api.send("POST", "/api/v1/joints", "positions=1", "page", {}, "application/x-www-form-urlencoded");
  EXPECT_EQ(form.status, 415);
  EXPECT_NE(form.body["error"].get<std::string>().find("Content-Type 'application/x-www-form-urlencoded' is not "
                                                       "allowed"),
            std::string::npos);
  EXPECT_EQ(api.send("POST", "/api/v1/joints", move, "page", {}, "text/plain").status, 415);
  EXPECT_EQ(api.send("POST", "/api/v1/joints", move, "page", {{"Host", "evil.example:" + port}}).status, 403);
  // Nothing ran: no job was queued, the joints stand where they stood.
  EXPECT_FALSE(api.worker().busy());
  const auto after = api.worker().snapshot();
  EXPECT_EQ(after.device, before.device);
  EXPECT_TRUE(after.last_error.empty());
}

TEST(WebApi, TokenOffTheLoopbackOrWhenGiven) {
  ServerOptions o;
  o.token = "0123456789abcdef";
  ApiServer api("xarm", o);
  EXPECT_NE(api.server().url().find("?token=0123456789abcdef"), std::string::npos);
  const Reply none = api.get("/api/v1/model");
  EXPECT_EQ(none.status, 401);
  EXPECT_NE(none.body["error"].get<std::string>().find("needs its token"), std::string::npos);
  EXPECT_EQ(api.get("/", "").status, 401);
  EXPECT_EQ(api.get("/api/v1/model", "", {{"Authorization", "Bearer 0123456789abcdef"}}).status, 200);
  EXPECT_EQ(api.get("/api/v1/model?token=0123456789abcdef").status, 200);
  EXPECT_EQ(api.get("/api/v1/model?token=wrong").status, 401);
  EXPECT_EQ(api.get("/api/v1/model", "", {{"Authorization", "Bearer wrong"}}).status, 401);
  const Reply stop = api.post("/api/v1/stop", json::object());
  EXPECT_EQ(stop.status, 401);
}

TEST(WebApi, NoTokenNoNonLoopbackListen) {
  auto session = session::open_arm_session("xarm", "").value();
  session::ArmWorker worker(std::move(session));
  ServerOptions o;
  o.host = "0.0.0.0";
  EXPECT_THROW(WebServer(worker, o), ArmctlError);
}

TEST(WebApi, APortInUseIsRefused) {
  ApiServer api;
  auto session = session::open_arm_session("xarm", "").value();
  session::ArmWorker worker(std::move(session));
  ServerOptions o;
  o.port = api.port();
  WebServer second(worker, o);
  try {
    second.start();
    ADD_FAILURE() << "a second server listens on port " << o.port;
  } catch (const ArmctlError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot listen on 127.0.0.1:" + std::to_string(o.port)), std::string::npos)
        << e.what();
  }
}

TEST(WebApi, ControlLease) {
  ApiServer api;
  api.first_positions();
  const std::string name = api.worker().model().joints[0].name;
  const json move{{"positions", {{name, 5}}}};
  Reply r = api.post("/api/v1/joints", move, "a");
  EXPECT_EQ(r.status, 409);
  EXPECT_NE(r.body["error"].get<std::string>().find("no client has control"), std::string::npos);
  r = api.post("/api/v1/control", {{"take", true}}, "a");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["control"]["you"], true);
  EXPECT_EQ(api.get("/api/v1/state", "a").body["control"]["you"], true);
  EXPECT_EQ(api.get("/api/v1/state", "b").body["control"]["you"], false);
  EXPECT_EQ(api.get("/api/v1/state", "b").body["control"]["holder"], true);
  // b takes over: a sees it, and a's moves are refused.
  ASSERT_EQ(api.post("/api/v1/control", {{"take", true}}, "b").status, 200);
  const Reply a_state = api.get("/api/v1/state", "a");
  EXPECT_EQ(a_state.body["control"]["you"], false);
  EXPECT_EQ(a_state.body["control"]["holder"], true);
  EXPECT_FALSE(a_state.body["control"]["since"].get<std::string>().empty());
  r = api.post("/api/v1/joints", move, "a");
  EXPECT_EQ(r.status, 409);
  EXPECT_NE(r.body["error"].get<std::string>().find("another client has control (since "), std::string::npos);
  for (const char* path : {"/api/v1/tool", "/api/v1/jog", "/api/v1/gripper", "/api/v1/torque", "/api/v1/clear-faults", "/api/v1/points",
                           "/api/v1/program/run", "/api/v1/groups/1/run"})
    EXPECT_EQ(api.post(path, json::object(), "a").status, 409) << path;
  EXPECT_EQ(api.post("/api/v1/control", {{"take", true}}).status, 400);  // no client id
  EXPECT_EQ(api.get("/api/v1/state", "", {{"X-Armctl-Client", "bad id!"}}).status, 400);
  ASSERT_EQ(api.post("/api/v1/control", {{"release", true}}, "b").status, 200);
  EXPECT_EQ(api.get("/api/v1/state", "a").body["control"]["holder"], false);
  EXPECT_FALSE(api.worker().busy());
}

// The events of the stream /api/v1/events, as they arrive (wall-clock times).
class EventReader {
 public:
  EventReader(ApiServer& api, const std::string& query = "") {
    thread_ = std::thread([this, &api, query] {
      auto c = api.client();
      c->Get(("/api/v1/events" + query).c_str(), [&](const char* data, std::size_t n) {
        std::lock_guard lock(mutex_);
        buffer_.append(data, n);
        for (auto end = buffer_.find("\n\n"); end != std::string::npos; end = buffer_.find("\n\n")) {
          const std::string event = buffer_.substr(0, end);
          buffer_.erase(0, end + 2);
          const auto data_at = event.find("data: ");
          if (event.rfind("event: state\n", 0) == 0 && data_at != std::string::npos)
            events_.push_back({std::chrono::steady_clock::now(), json::parse(event.substr(data_at + 6))});
        }
        arrived_.notify_all();
        return !stop_;
      });
    });
  }
  ~EventReader() {
    stop_ = true;
    thread_.join();
  }
  struct Event {
    std::chrono::steady_clock::time_point at;
    json state;
  };
  std::vector<Event> events() {
    std::lock_guard lock(mutex_);
    return events_;
  }
  // Waits (wall clock, bounded) until `n` events arrived.
  bool wait_for(std::size_t n, std::chrono::seconds timeout = 20s) {
    std::unique_lock lock(mutex_);
    return arrived_.wait_for(lock, timeout, [&] { return events_.size() >= n; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::string buffer_;
  std::vector<Event> events_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST(WebApi, EventsIdleKeepAliveAndWhileMoving) {
  ApiServer api;
  api.first_positions();
  {
    EventReader idle(api, "?client=watcher");
    ASSERT_TRUE(idle.wait_for(3));
    const auto e = idle.events();
    EXPECT_EQ(e[0].state["control"]["you"], false);
    EXPECT_TRUE(e[0].state["joints"].is_array());
    // At least one per idle interval (500 ms) even when nothing changes: 3 within 2 s.
    EXPECT_LT(e[2].at - e[0].at, 2s);
  }
  api.take("page");
  const auto& model = api.worker().model();
  // A slow move of the base joint across most of its range.
  const json move{{"positions", {{model.joints[0].name, model.joints[0].limits.upper * 180 / M_PI * 0.8}}},
                  {"speed", 0.15}};
  EventReader moving(api, "?client=page");
  ASSERT_TRUE(moving.wait_for(1));
  const Reply r = api.post("/api/v1/joints", move, "page");
  ASSERT_EQ(r.status, 200) << r.text;
  ASSERT_GT(r.body["duration_s"].get<double>(), 1.0);
  ASSERT_TRUE(api.wait_idle());
  // The events while the move ran: the ones that show a job.
  std::vector<EventReader::Event> during;
  for (const auto& e : moving.events())
    if (!e.state["job"].get<std::string>().empty()) during.push_back(e);
  ASSERT_GE(during.size(), 2u);
  const double seconds = std::chrono::duration<double>(during.back().at - during.front().at).count();
  const double rate = double(during.size() - 1) / seconds;
  std::printf("SSE while moving: %zu events in %.2f s = %.0f /s\n", during.size(), seconds, rate);
  EXPECT_GE(rate, 20.0);
  EXPECT_EQ(during.front().state["control"]["you"], true);
  bool saw_motion = false;
  for (const auto& e : during) saw_motion = saw_motion || e.state["motion"].is_object();
  EXPECT_TRUE(saw_motion);
}

}  // namespace
}  // namespace armctl::web::testing

namespace armctl::web::testing {
namespace {

// What a raw HTTP request gets back (the status line and what follows), read until the
// server closes or has sent `until`.
std::string raw_request(int port, const std::string& request, const std::string& until) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(std::uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  EXPECT_EQ(::send(fd, request.data(), request.size(), 0), ssize_t(request.size()));
  std::string got;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    got.append(buffer, std::size_t(n));
    if (got.find(until) != std::string::npos) break;
  }
  ::close(fd);
  return got;
}

TEST(WebApi, StopWithoutAnyBodyAnswersAtOnce) {
  ApiServer api;
  api.first_positions();
  const std::string host = "Host: 127.0.0.1:" + std::to_string(api.port()) + "\r\n";
  const auto began = std::chrono::steady_clock::now();
  // curl -X POST: no Content-Length, no body. HTTP/1.1 says there is none: no waiting for one.
  const std::string got = raw_request(api.port(), "POST /api/v1/stop HTTP/1.1\r\n" + host + "\r\n", "\"stopped\":true");
  EXPECT_EQ(got.rfind("HTTP/1.1 200", 0), 0u) << got;
  EXPECT_NE(got.find("\"stopped\":true"), std::string::npos) << got;
  EXPECT_LT(std::chrono::steady_clock::now() - began, 2s);
  // Nor is a STOP refused for its body's type; the Host and Origin checks still hold.
  EXPECT_EQ(api.send("POST", "/api/v1/stop", "stop!", "", {}, "text/plain").status, 200);
  EXPECT_EQ(api.send("POST", "/api/v1/stop", "{}", "", {{"Origin", "http://evil.example"}}).status, 403);
}

}  // namespace
}  // namespace armctl::web::testing

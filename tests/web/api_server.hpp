// The API on loopback for the tests: an arm on its embedded simulator, its worker, and the
// server on a free port, with an httplib client that sends what the page sends (Host is
// httplib's own; X-Armctl-Client and JSON bodies as asked).
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/regular_file.hpp"
#include "session/arm_session.hpp"
#include "session/arm_worker.hpp"
#include "web/httplib.hpp"
#include "web/web_server.hpp"

namespace armctl::web::testing {

using json = nlohmann::json;
using namespace std::chrono_literals;

struct Reply {
  int status = 0;
  json body;          // parsed when JSON, else null
  std::string text;   // as sent
  std::string content_type;
  httplib::Headers headers;
};

class ApiServer {
 public:
  // `device`: a device URI ("" = the arm's embedded simulator); `scene`: a scene file, as
  // `armctl serve --scene FILE` takes it.
  explicit ApiServer(const std::string& arm_name = "xarm", ServerOptions options = {}, const std::string& device = "",
                     const std::filesystem::path& scene = {}) {
    session::SessionOptions session_options;
    session_options.reconnect = true;  // as `armctl serve` opens it
    session_options.scene = scene;
    auto session = armctl::session::open_arm_session(arm_name, device, session_options).value();
    options.port = 0;
    if (options.host.empty()) options.host = "127.0.0.1";
    options.device = describe_device(*session, device);
    worker_ = std::make_unique<session::ArmWorker>(std::move(session));
    server_ = std::make_unique<WebServer>(*worker_, options);
    server_->start();
  }
  ~ApiServer() {
    server_->stop();
    server_.reset();
    worker_.reset();
  }

  session::ArmWorker& worker() { return *worker_; }
  WebServer& server() { return *server_; }
  int port() const { return server_->port(); }

  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", server_->port());
    c->set_read_timeout(30, 0);
    return c;
  }

  static Reply reply_of(const httplib::Result& r) {
    Reply out;
    if (!r) {
      ADD_FAILURE() << "no answer: " << httplib::to_string(r.error());
      return out;
    }
    out.status = r->status;
    out.text = r->body;
    out.content_type = r->get_header_value("Content-Type");
    out.headers = r->headers;
    if (out.content_type.rfind("application/json", 0) == 0) out.body = json::parse(r->body, nullptr, false);
    return out;
  }

  // A request as the page makes it, from client `id` ("" = no X-Armctl-Client header).
  Reply get(const std::string& path, const std::string& id = "", httplib::Headers headers = {}) const {
    if (!id.empty()) headers.emplace("X-Armctl-Client", id);
    return reply_of(client()->Get(path, headers));
  }
  Reply send(const std::string& method, const std::string& path, const std::string& body, const std::string& id = "",
             httplib::Headers headers = {}, const std::string& type = "application/json") const {
    if (!id.empty()) headers.emplace("X-Armctl-Client", id);
    auto c = client();
    if (method == "POST") return reply_of(c->Post(path, headers, body, type));
    if (method == "PUT") return reply_of(c->Put(path, headers, body, type));
    if (method == "DELETE") return reply_of(c->Delete(path, headers, body, type));
    ADD_FAILURE() << method;
    return {};
  }
  Reply post(const std::string& path, const json& body, const std::string& id = "") const {
    return send("POST", path, body.dump(), id);
  }

  // Takes control for `id`.
  void take(const std::string& id) const {
    auto r = post("/api/v1/control", {{"take", true}}, id);
    ASSERT_EQ(r.status, 200) << r.text;
  }

  // Waits (on the worker's published snapshots, at most `timeout`) until `done` holds.
  template <typename F>
  bool wait_until(F done, std::chrono::milliseconds timeout = 20s) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    auto s = worker_->snapshot();
    while (!done(s)) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      s = worker_->wait_for_update(s.sequence, 200ms);
    }
    return true;
  }
  // The first snapshot with positions.
  session::ArmSnapshot first_positions() {
    EXPECT_TRUE(wait_until([](const session::ArmSnapshot& s) { return !s.positions.empty(); }));
    return worker_->snapshot();
  }
  // Until the worker runs no job.
  bool wait_idle(std::chrono::milliseconds timeout = 30s) {
    return wait_until([this](const session::ArmSnapshot& s) { return s.job.empty() && !worker_->busy(); }, timeout);
  }

 private:
  std::unique_ptr<session::ArmWorker> worker_;
  std::unique_ptr<WebServer> server_;
};

}  // namespace armctl::web::testing

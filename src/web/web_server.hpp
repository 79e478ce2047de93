// `armctl serve`'s server: the JSON HTTP API of docs/http-api.md and the dashboard's
// embedded files, over one arm worker (session/arm_worker.hpp), which every arm access goes
// through. Every request first passes the security checks (web/security.hpp); requests that
// move or change the arm need the control lease (web/control_lease.hpp), except STOP.
#pragma once

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "session/arm_worker.hpp"
#include "web/connection_limits.hpp"
#include "web/state_json.hpp"

namespace httplib {
struct Request;
struct Response;
}

namespace armctl::web {

class GuardedServer;

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port (tests)
  // Needed on every request when not empty; serve makes one up off the loopback address.
  std::string token;
  // Where POST /api/v1/points saves (program points-file format); "" keeps them in memory.
  std::filesystem::path points_file;
  DeviceInfo device;
  // SSE: a state event at least this often while nothing changes (a keep-alive).
  std::chrono::milliseconds idle_event_interval{500};
  // A holder of control with no event stream open loses it after this long without a
  // request (web/control_lease.hpp).
  std::chrono::milliseconds control_idle = std::chrono::seconds(60);
  // ... and this long after its page's last event stream closed (a reload, a closed tab).
  std::chrono::milliseconds control_grace = std::chrono::seconds(5);
  // Connections, request time and event streams (web/connection_guard.hpp).
  ConnectionLimits limits;
};

class WebServer {
 public:
  // Throws ArmctlError when the points file cannot be read, or off loopback without a token.
  WebServer(session::ArmWorker& worker, ServerOptions options);
  ~WebServer();  // stop()
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  // Binds the listen address (throws ArmctlError(io) naming it if that fails) and serves
  // on a thread of its own until stop().
  void start();
  // Stops serving: open event streams end, the listening socket closes. Idempotent.
  void stop();
  int port() const { return port_; }
  // http://HOST:PORT/ with ?token=T when a token is needed.
  std::string url() const;
  // The open connections and event streams (tests, diagnostics).
  ConnectionCounts connections() const;

  struct State;  // everything the handlers share (web_server.cpp)

 private:
  std::unique_ptr<State> state_;
  std::unique_ptr<GuardedServer> http_;
  std::function<void(const httplib::Request&, httplib::Response&)> dispatch_;  // routes, then files
  std::thread thread_;
  // Watches who holds control (State::control_changed): an idle holder's control ends only
  // when somebody asks, and a page that closed asks nothing.
  void watch_control();
  std::thread watcher_;
  std::mutex watcher_mutex_;
  std::condition_variable watcher_wake_;
  bool watcher_stop_ = false;
  int port_ = 0;
  std::atomic<bool> listen_ended_{false};
};

}  // namespace armctl::web

#include "web/web_server.hpp"

#include <sys/socket.h>

#include <future>

#include <fmt/core.h>
#include "web/httplib.hpp"

#include "core/printable.hpp"
#include "web/api_error.hpp"
#include "web/error_detail.hpp"
#include "web/connection_guard.hpp"
#include "web/request_body.hpp"
#include "web/server_state.hpp"
#include "web/static_assets.hpp"

namespace armctl::web {

namespace {

using namespace std::chrono_literals;

std::optional<std::string_view> header(const httplib::Request& r, const char* name) {
  auto it = r.headers.find(name);
  if (it == r.headers.end()) return std::nullopt;
  return std::string_view(it->second);
}

std::optional<std::string_view> parameter(const httplib::Request& r, const char* name) {
  auto it = r.params.find(name);
  if (it == r.params.end()) return std::nullopt;
  return std::string_view(it->second);
}

bool has_body(const httplib::Request& r) {
  if (auto te = header(r, "Transfer-Encoding"); te && te->find("chunked") != std::string_view::npos) return true;
  auto length = header(r, "Content-Length");
  return length && *length != "0";
}

std::string client_of(const httplib::Request& r) {
  if (auto h = header(r, "X-Armctl-Client")) return check_client_id(*h, true);
  // EventSource cannot send headers: the page names itself in the URL.
  if (auto p = parameter(r, "client")) return check_client_id(*p, true);
  return "";
}

// Everything the page loads is its own: scripts, styles, the URDF and meshes, the API
// (fetch and the event stream); three.js makes blob: URLs for textures.
constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; img-src 'self' data: blob:; object-src 'none'; base-uri 'none'; "
    "form-action 'self'; frame-ancestors 'none'";

// The page, with a nonce of its own on its one inline script (the boot script that writes
// the import map, whose text depends on the page's token): the policy allows that script and
// the import map it adds, and no other inline script (an injected one is not run).
void serve_page(const StaticAsset& page, httplib::Response& res) {
  const std::string nonce = make_token();
  std::string html(page.data());
  const std::string tag = "<script>";
  if (auto at = html.find(tag); at != std::string::npos) html.replace(at, tag.size(), "<script nonce=\"" + nonce + "\">");
  res.headers.erase("Content-Security-Policy");
  res.set_header("Content-Security-Policy",
                 fmt::format("{}; script-src 'self' 'nonce-{}'", kContentSecurityPolicy, nonce));
  res.set_content(std::move(html), content_type_for(page.path));
}

const char* status_text(int status) {
  switch (status) {
    case 400: return "the request is malformed";
    case 404: return "no such path";
    case 405: return "method not allowed";
    case 413: return "the request body is larger than 1 MiB (1048576 bytes), the most allowed";
    case 414: return "the request's URL is too long";
    case 416: return "the Range header is not valid or names no part of the file";
    default: return "the request failed";
  }
}

}  // namespace

json WebServer::State::start_motion(const std::string& what, MotionJob job) {
  struct Acceptance {
    std::mutex mutex;
    std::optional<Result<json>> answer;
    std::condition_variable changed;
    void set(Result<json> a) {
      std::lock_guard lock(mutex);
      if (!answer) answer = std::move(a);
      changed.notify_all();
    }
  };
  auto acceptance = std::make_shared<Acceptance>();
  auto finished = worker.run(what, [acceptance, job](arm::Arm& arm, session::JobContext& ctx) -> Status {
    Accept accept = [&](Result<json> a) { acceptance->set(std::move(a)); };
    return job(arm, ctx, accept);
  });
  // The job runs on the worker; it may also never run (busy, dropped by a stop): then its
  // result says why. A job that ends without accepting (refused, or done at once) answers
  // through `finished`, which the worker sets once it is idle again: the client's next
  // request then finds it free.
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  std::unique_lock lock(acceptance->mutex);
  while (!acceptance->answer) {
    if (finished.wait_for(0s) == std::future_status::ready) {
      lock.unlock();
      Status s = finished.get();
      lock.lock();
      if (!acceptance->answer) {
        if (!s) fail(s.error());
        return json{{"done", true}};
      }
      break;
    }
    if (std::chrono::steady_clock::now() > deadline)
      throw ApiError(500, fmt::format("{}: the arm worker did not start it within 30 s", what));
    acceptance->changed.wait_for(lock, 5ms);
  }
  Result<json> answer = *acceptance->answer;
  lock.unlock();
  if (!answer) {
    // Refused before it moved: the job is ending. Answer once the worker is free again, so
    // that the next request does not find it busy with this one.
    finished.wait_for(30s);
    fail(answer.error());
  }
  return *answer;
}

void WebServer::State::run_to_end(const std::string& what, session::ArmWorker::Job job) {
  auto finished = worker.run(what, std::move(job));
  if (finished.wait_for(30s) != std::future_status::ready)
    throw ApiError(500, fmt::format("{}: no answer from the arm within 30 s", what));
  Status s = finished.get();
  if (!s) fail(s.error());
}

json WebServer::State::state_for(const std::string& client, const session::ArmSnapshot& snapshot) {
  return state_json(kinematics(), options.device, snapshot, lease.view(client), program.view());
}

WebServer::WebServer(session::ArmWorker& worker, ServerOptions options)
    : state_(std::make_unique<State>(worker, std::move(options))),
      http_(std::make_unique<GuardedServer>(state_->options.limits)) {
  State& s = *state_;
  if (!is_loopback(s.options.host) && s.options.token.empty())
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("listening on {} (not the loopback address) needs a token", s.options.host));
  s.policy = {s.options.host, s.options.port, s.options.token};
  if (!s.options.points_file.empty()) {
    std::error_code ec;
    if (std::filesystem::exists(s.options.points_file, ec)) {
      auto read = files::read_points_file(s.options.points_file);
      if (!read) throw ArmctlError(read.error());
      s.points = std::move(read).value();
    }
  }
  s.router.error_detail = [&s](json& body, const Error& e) { add_error_detail(body, e, s.worker.model()); };
  add_arm_routes(s);
  add_point_routes(s);
  add_scene_routes(s);
  add_group_routes(s);
  add_program_routes(s);
  add_calibration_routes(s);

  GuardedServer& http = *http_;
  s.connections = &http.connections();
  // A thread per connection (a pool's fixed count was what slow clients and event streams
  // used up, leaving none for STOP); the connection table bounds how many are open.
  const std::size_t hard_limit = 4 * s.options.limits.max_connections;
  http.new_task_queue = [hard_limit] { return new ConnectionThreads(hard_limit); };
  // Framing the page would let another site have its buttons clicked (clickjacking); the
  // page loads only its own files, and its scripts and styles are files, not inline.
  http.set_default_headers({
      {"X-Frame-Options", "DENY"},
      {"Content-Security-Policy", kContentSecurityPolicy},
      {"X-Content-Type-Options", "nosniff"},
      {"Referrer-Policy", "no-referrer"},
  });
  http.set_payload_max_length(kMaxBodyBytes);
  // SO_REUSEADDR only: httplib's default SO_REUSEPORT would let a second server bind the same
  // port and share the requests (two arms behind one URL).
  http.set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  http.set_keep_alive_max_count(1000);
  // An idle keep-alive connection holds a thread, and stop() waits for it: not for long.
  http.set_keep_alive_timeout(2);
  dispatch_ = [this](const httplib::Request& r, httplib::Response& res) {
    State& st = *state_;
    std::string client;
    try {
      client = client_of(r);
    } catch (const ApiError& e) {
      return reply_error(res, e.status(), e.what());
    }
    if (!client.empty()) st.lease.seen(client);
    if (st.router.dispatch(r, res, client)) return;
    if (r.method == "GET" || r.method == "HEAD") {
      if (const StaticAsset* a = find_asset(r.path)) {
        res.set_header("Cache-Control", "no-cache");
        if (std::string_view(a->path) == "/index.html") return serve_page(*a, res);
        res.set_content(std::string(a->data()), content_type_for(a->path));
        return;
      }
    } else if (find_asset(r.path)) {
      res.set_header("Allow", "GET, HEAD");
      return reply_error(res, 405, fmt::format("{} is not allowed on {}; allowed: GET", printable(r.method),
                                               printable(r.path)));
    }
    reply_error(res, 404, fmt::format("no such path: {}", printable(r.path.substr(0, 200))));
  };
  http.set_pre_routing_handler([this](const httplib::Request& r, httplib::Response& res) {
    State& st = *state_;
    RequestFacts facts{r.method,
                       header(r, "Host"),
                       header(r, "Origin"),
                       header(r, "Content-Type"),
                       has_body(r),
                       header(r, "Authorization"),
                       parameter(r, "token"),
                       header(r, "Referer")};
    // A STOP is never refused for its form (its body is not read): any type will do.
    if (r.path == "/api/v1/stop") facts.has_body = false;
    // httplib adds four headers of its own (REMOTE_ADDR, REMOTE_PORT, LOCAL_ADDR, LOCAL_PORT).
    if (r.headers.size() > st.options.limits.max_header_count + 4) {
      reply_error(res, 431,
                  fmt::format("the request has {} header lines; at most {} are allowed", r.headers.size() - 4,
                              st.options.limits.max_header_count));
      return httplib::Server::HandlerResponse::Handled;
    }
    if (auto refusal = check_request(st.policy, facts)) {
      reply_error(res, refusal->status, refusal->message);
      return httplib::Server::HandlerResponse::Handled;
    }
    // A request without Content-Length or chunked body has no body (HTTP/1.1), but httplib
    // would wait for one until its read timeout (`curl -X POST .../stop`): answer it now.
    if (r.method != "GET" && r.method != "HEAD" && !has_body(r) && !header(r, "Content-Length")) {
      dispatch_(r, res);
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  auto dispatch = [this](const httplib::Request& r, httplib::Response& res) { dispatch_(r, res); };
  http.Get(".*", dispatch);
  http.Post(".*", dispatch);
  http.Put(".*", dispatch);
  http.Delete(".*", dispatch);
  http.Patch(".*", dispatch);
  http.Options(".*", dispatch);
  // httplib's own refusals (a body over the limit, a malformed request) in the API's form.
  http.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request&, httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    reply_error(res, res.status, status_text(res.status));
    return httplib::Server::HandlerResponse::Handled;
  }));
  http.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    std::string what = "unknown";
    try {
      if (ep) std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    reply_error(res, 500, fmt::format("internal error: {}", printable(what)));
  });
}

using namespace std::chrono_literals;

WebServer::~WebServer() { stop(); }

void WebServer::start() {
  State& s = *state_;
  if (s.options.port == 0) {
    port_ = http_->bind_to_any_port(s.options.host);
  } else {
    port_ = http_->bind_to_port(s.options.host, s.options.port) ? s.options.port : -1;
  }
  if (port_ <= 0)
    throw ArmctlError(ErrorKind::io, fmt::format("cannot listen on {}:{} (in use, or not an address of this machine)",
                                                 s.options.host, s.options.port));
  s.policy.port = port_;
  thread_ = std::thread([this] {
    http_->listen_after_bind();
    listen_ended_ = true;
  });
  watcher_ = std::thread([this] { watch_control(); });
}

void WebServer::watch_control() {
  // Often enough that a calibration left with its torque off by a closed page is held again
  // within a second of its control ending (web/control_lease.hpp: 5 s after the page went).
  constexpr auto kEvery = std::chrono::milliseconds(250);
  std::optional<std::string> last = state_->lease.holder();
  std::unique_lock lock(watcher_mutex_);
  while (!watcher_wake_.wait_for(lock, kEvery, [this] { return watcher_stop_; })) {
    std::optional<std::string> now = state_->lease.holder();
    if (now == last) continue;
    last = std::move(now);
    lock.unlock();
    for (const auto& changed : state_->control_changed) changed(last);
    lock.lock();
  }
}

void WebServer::stop() {
  state_->stopping = true;
  {
    std::lock_guard lock(watcher_mutex_);
    watcher_stop_ = true;
  }
  watcher_wake_.notify_all();
  if (watcher_.joinable()) watcher_.join();
  // httplib's stop() does nothing until its loop runs: wait for that (or for its end).
  while (thread_.joinable() && !http_->is_running() && !listen_ended_) std::this_thread::sleep_for(1ms);
  http_->stop();
  http_->connections().close_idle();
  if (thread_.joinable()) thread_.join();
  // Jobs started here use the server's state (a program's progress): they end before it goes.
  session::ArmWorker& worker = state_->worker;
  if (worker.busy()) worker.command(arm::MotionCommand::stop);
  auto snapshot = worker.snapshot();
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (worker.busy() && std::chrono::steady_clock::now() < deadline)
    snapshot = worker.wait_for_update(snapshot.sequence, 100ms);
}

ConnectionCounts WebServer::connections() const { return http_->connections().counts(); }

std::string WebServer::url() const {
  const std::string& host = state_->options.host;
  const std::string shown = host.find(':') != std::string::npos ? "[" + host + "]" : host;
  return fmt::format("http://{}:{}/{}", shown, port_,
                     state_->options.token.empty() ? "" : "?token=" + state_->options.token);
}

}  // namespace armctl::web

// What a hostile or careless client cannot do to `armctl serve` (web/connection_guard.hpp,
// docs/http-api.md "Limits"): with many event streams and slow connections open, STOP is
// answered and the arm comes to rest; a flood of connections closes the oldest idle ones; a
// request that dribbles in is cut off; streams have a budget; the page cannot be framed;
// too many header lines and multi-range requests do not cost the server.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <vector>

#include <fmt/core.h>

#include "api_server.hpp"
#include "web/static_assets.hpp"

namespace armctl::web::testing {
namespace {

// A TCP connection to the server that sends exactly what a test writes.
class RawConnection {
 public:
  explicit RawConnection(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~RawConnection() { ::close(fd_); }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  bool connected() const { return connected_; }
  bool send(const std::string& text) { return ::send(fd_, text.data(), text.size(), MSG_NOSIGNAL) == ssize_t(text.size()); }
  // What arrives within `timeout`, up to the first `until` (or the connection's end).
  std::string receive(std::chrono::milliseconds timeout, const std::string& until = "\r\n\r\n") {
    std::string got;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (got.find(until) == std::string::npos) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
      char buffer[4096];
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) {
        closed_ = true;
        break;
      }
      got.append(buffer, std::size_t(n));
    }
    return got;
  }
  // True when the server closes the connection within `timeout` (whatever it sent first).
  bool closed_within(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!closed_ && std::chrono::steady_clock::now() < deadline) receive(timeout, "\x01never");
    return closed_;
  }

 private:
  int fd_;
  bool connected_ = false;
  bool closed_ = false;
};

std::string request_head(int port, const std::string& line) {
  return fmt::format("{}\r\nHost: 127.0.0.1:{}\r\n", line, port);
}

// An event stream as a dashboard tab opens it: the answer's head arrives and it stays open.
std::unique_ptr<RawConnection> open_stream(int port, const std::string& client) {
  auto c = std::make_unique<RawConnection>(port);
  EXPECT_TRUE(c->connected());
  c->send(request_head(port, "GET /api/v1/events?client=" + client + " HTTP/1.1") + "\r\n");
  const std::string head = c->receive(10s);
  EXPECT_NE(head.find("200"), std::string::npos) << head;
  return c;
}

// A slowloris: the request line and one header, and the rest never comes.
std::unique_ptr<RawConnection> open_slow(int port) {
  auto c = std::make_unique<RawConnection>(port);
  EXPECT_TRUE(c->connected());
  c->send(request_head(port, "POST /api/v1/stop HTTP/1.1") + "X-Slow: 1\r\n");
  return c;
}

double deg(double rad) { return rad * 180 / M_PI; }

TEST(WebLimits, StopIsAnsweredWithManyStreamsAndSlowConnectionsOpen) {
  ApiServer api("xarm");
  const auto before = api.first_positions();
  api.take("page");
  const auto& j = api.worker().model().joints[0];
  const double target = deg(j.limits.upper) * 0.9;
  ASSERT_EQ(api.post("/api/v1/joints", {{"positions", {{j.name, target}}}, {"speed", 0.05}}, "page").status, 200);

  // 20 tabs (more than the old pool's 16 threads) and 40 slow connections.
  std::vector<std::unique_ptr<RawConnection>> held;
  for (int i = 0; i < 20; ++i) held.push_back(open_stream(api.port(), fmt::format("tab{}", i)));
  for (int i = 0; i < 40; ++i) held.push_back(open_slow(api.port()));
  ASSERT_TRUE(api.wait_until([&](const session::ArmSnapshot& s) {
    return !s.job.empty() && std::abs(s.positions[0] - before.positions[0]) > 0.05;
  })) << "the move did not start";

  auto client = api.client();
  client->set_read_timeout(3, 0);  // far less than the move's remaining time
  auto stop = client->Post("/api/v1/stop", "{}", "application/json");
  ASSERT_TRUE(stop) << "STOP got no answer: " << httplib::to_string(stop.error());
  EXPECT_EQ(stop->status, 200) << stop->body;
  // The page and the state are served too.
  EXPECT_EQ(api.get("/").status, 200);
  EXPECT_EQ(api.get("/api/v1/state").status, 200);
  ASSERT_TRUE(api.wait_idle(5s));
  std::vector<double> previous;
  ASSERT_TRUE(api.wait_until(
      [&](const session::ArmSnapshot& s) {
        const bool rest = s.device == previous;
        previous = s.device;
        return rest;
      },
      5s));
  EXPECT_LT(deg(api.worker().snapshot().positions[0]), target - 5) << "the move was not stopped";
  EXPECT_EQ(api.server().connections().streams, 20u);
}

TEST(WebLimits, AFloodOfConnectionsClosesTheOldestIdleOnesAndStopIsAnswered) {
  ServerOptions options;
  options.limits.max_connections = 16;
  options.limits.max_connections_per_address = 12;
  ApiServer api("xarm", options);
  std::vector<std::unique_ptr<RawConnection>> flood;
  for (int i = 0; i < 40; ++i) flood.push_back(open_slow(api.port()));
  // Every flood connection was taken (registered) before STOP's: each new one beyond the
  // bound closed an older idle one, and STOP, the newest, is answered.
  ASSERT_TRUE(api.wait_until([&](const session::ArmSnapshot&) { return api.server().connections().evicted >= 28; },
                             10s))
      << "evicted " << api.server().connections().evicted;
  auto client = api.client();
  client->set_read_timeout(3, 0);
  auto stop = client->Post("/api/v1/stop", "{}", "application/json");
  ASSERT_TRUE(stop) << httplib::to_string(stop.error());
  EXPECT_EQ(stop->status, 200);
  EXPECT_TRUE(flood.front()->closed_within(5s)) << "the oldest slow connection is still open";
  EXPECT_LE(api.server().connections().connections, 12u + 1);
}

TEST(WebLimits, ARequestThatDoesNotArriveInTimeIsCutOff) {
  ServerOptions options;
  options.limits.request_time = 300ms;
  ApiServer api("xarm", options);
  RawConnection slow(api.port());
  ASSERT_TRUE(slow.send(request_head(api.port(), "GET /api/v1/state HTTP/1.1")));
  // One header line every 100 ms (each within the per-read timeout): still cut off.
  const auto start = std::chrono::steady_clock::now();
  bool closed = false;
  for (int i = 0; i < 50 && !closed; ++i) {
    slow.send(fmt::format("X-Line-{}: 1\r\n", i));
    closed = slow.closed_within(100ms);
  }
  EXPECT_TRUE(closed) << "a request dribbling in for 5 s was not cut off";
  EXPECT_LT(std::chrono::steady_clock::now() - start, 3s);
  // An ordinary request is answered.
  EXPECT_EQ(api.get("/api/v1/state").status, 200);
}

TEST(WebLimits, EventStreamsHaveABudget) {
  ServerOptions options;
  options.limits.max_event_streams = 3;
  options.limits.max_event_streams_per_client = 2;
  ApiServer api("xarm", options);
  auto a1 = open_stream(api.port(), "a");
  auto a2 = open_stream(api.port(), "a");
  RawConnection a3(api.port());
  a3.send(request_head(api.port(), "GET /api/v1/events?client=a HTTP/1.1") + "\r\n");
  std::string answer = a3.receive(5s, "}");
  EXPECT_NE(answer.find("503"), std::string::npos) << answer;
  EXPECT_NE(answer.find("the most allowed for one page"), std::string::npos) << answer;
  auto b1 = open_stream(api.port(), "b");
  RawConnection b2(api.port());
  b2.send(request_head(api.port(), "GET /api/v1/events?client=b HTTP/1.1") + "\r\n");
  answer = b2.receive(5s, "}");
  EXPECT_NE(answer.find("503"), std::string::npos) << answer;
  EXPECT_NE(answer.find("3 event streams are open"), std::string::npos) << answer;
  // A closed tab gives its stream back.
  a1.reset();
  ASSERT_TRUE(api.wait_until([&](const session::ArmSnapshot&) { return api.server().connections().streams == 2; }, 10s));
  auto c1 = open_stream(api.port(), "c");
  EXPECT_EQ(api.server().connections().streams, 3u);
}

TEST(WebLimits, ControlEndsWhenThePageThatHoldsItGoesAway) {
  ServerOptions options;
  options.control_grace = 200ms;
  ApiServer api("xarm", options);
  auto stream = open_stream(api.port(), "page");
  api.take("page");
  EXPECT_EQ(api.get("/api/v1/state", "other").body["control"]["holder"], true);
  stream.reset();  // the tab is closed or reloaded
  ASSERT_TRUE(api.wait_until(
      [&](const session::ArmSnapshot&) { return api.get("/api/v1/state", "other").body["control"]["holder"] == false; },
      10s));
  // The reloaded page (a new id) takes it without "another client has control".
  auto reloaded = open_stream(api.port(), "page-2");
  api.take("page-2");
  EXPECT_EQ(api.get("/api/v1/state", "page-2").body["control"]["you"], true);
}

TEST(WebLimits, ThePageCannotBeFramedAndRunsOnlyItsOwnScripts) {
  ApiServer api("xarm");
  const Reply page = api.get("/");
  ASSERT_EQ(page.status, 200);
  auto header = [](const Reply& r, const char* name) {
    auto it = r.headers.find(name);
    return it == r.headers.end() ? std::string() : it->second;
  };
  EXPECT_EQ(header(page, "X-Frame-Options"), "DENY");
  EXPECT_EQ(page.headers.count("Content-Security-Policy"), 1u);
  const std::string csp = header(page, "Content-Security-Policy");
  EXPECT_NE(csp.find("frame-ancestors 'none'"), std::string::npos) << csp;
  EXPECT_NE(csp.find("default-src 'self'"), std::string::npos) << csp;
  // The boot script carries the nonce the policy names, and only it; a new one each time.
  const auto at = csp.find("'nonce-");
  ASSERT_NE(at, std::string::npos) << csp;
  const std::string nonce = csp.substr(at + 7, csp.find('\'', at + 7) - at - 7);
  EXPECT_NE(page.text.find("<script nonce=\"" + nonce + "\">"), std::string::npos);
  EXPECT_EQ(page.text.find("<script>"), std::string::npos);
  EXPECT_EQ(header(api.get("/"), "Content-Security-Policy").find(nonce), std::string::npos);
  // The API and the other files carry the policy and the framing refusal too.
  const Reply state = api.get("/api/v1/state");
  EXPECT_EQ(header(state, "X-Frame-Options"), "DENY");
  EXPECT_NE(header(state, "Content-Security-Policy").find("frame-ancestors 'none'"), std::string::npos);
}

TEST(WebLimits, TooManyHeaderLinesAreRefused) {
  ApiServer api("xarm");
  httplib::Headers many;
  for (int i = 0; i < 150; ++i) many.emplace(fmt::format("X-Line-{}", i), "1");
  const Reply r = api.get("/api/v1/state", "", many);
  EXPECT_EQ(r.status, 431) << r.text;
  EXPECT_NE(r.body["error"].get<std::string>().find("at most 100 are allowed"), std::string::npos) << r.text;
  // A head larger than 64 KiB is not read to its end.
  RawConnection huge(api.port());
  huge.send(request_head(api.port(), "GET /api/v1/state HTTP/1.1"));
  const std::string line = "X-Big: " + std::string(8000, 'a') + "\r\n";
  for (int i = 0; i < 20; ++i) huge.send(line);
  EXPECT_TRUE(huge.closed_within(5s));
}

TEST(WebLimits, ManyRangesGetTheWholeFileOnceAndOneRangeIsHonoured) {
  ApiServer api("xarm");
  const StaticAsset* largest = nullptr;
  for (const auto& a : static_assets())
    if (!largest || a.data().size() > largest->data().size()) largest = &a;
  ASSERT_NE(largest, nullptr);
  std::string ranges = "bytes=0-";
  for (int i = 1; i < 40; ++i) ranges += ",0-";
  const Reply many = api.get(largest->path, "", {{"Range", ranges}});
  EXPECT_EQ(many.status, 200);
  EXPECT_EQ(many.text.size(), largest->data().size());
  const Reply one = api.get(largest->path, "", {{"Range", "bytes=0-99"}});
  EXPECT_EQ(one.status, 206);
  EXPECT_EQ(one.text, std::string(largest->data().substr(0, 100)));
}

TEST(WebLimits, ARepeatedJsonKeyIsRefused) {
  ApiServer api("xarm");
  api.first_positions();
  api.take("page");
  const Reply r = api.send("POST", "/api/v1/joints", R"({"positions": {"servo1": 10}, "speed": 0.1, "speed": 1})",
                           "page");
  EXPECT_EQ(r.status, 400) << r.text;
  EXPECT_NE(r.body["error"].get<std::string>().find("key \"speed\" appears twice"), std::string::npos) << r.text;
  EXPECT_FALSE(api.worker().busy());
}

TEST(WebLimits, ARefererFromAnotherSiteCannotMoveTheArm) {
  ApiServer api("xarm");
  api.first_positions();
  api.take("page");
  const Reply r = api.send("POST", "/api/v1/gripper", R"({"closed": 0.5})", "page",
                           {{"Referer", "http://evil.example/attack.html"}});
  EXPECT_EQ(r.status, 403) << r.text;
  EXPECT_NE(r.body["error"].get<std::string>().find("Referer"), std::string::npos) << r.text;
  EXPECT_FALSE(api.worker().busy());
}

}  // namespace
}  // namespace armctl::web::testing

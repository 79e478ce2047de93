#include "web/connection_guard.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <thread>

#include <fmt/core.h>

namespace armctl::web {

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

thread_local int current_connection = -1;

// The address and port at either end of a connected socket ("" and 0 when unknown).
struct Endpoint {
  std::string address;
  int port = 0;
};

Endpoint endpoint_of(int socket, bool peer) {
  sockaddr_storage a{};
  socklen_t n = sizeof a;
  if ((peer ? ::getpeername(socket, reinterpret_cast<sockaddr*>(&a), &n)
            : ::getsockname(socket, reinterpret_cast<sockaddr*>(&a), &n)) != 0)
    return {};
  char text[INET6_ADDRSTRLEN] = {};
  if (a.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<sockaddr_in*>(&a);
    ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
    return {text, ntohs(v4->sin_port)};
  }
  if (a.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<sockaddr_in6*>(&a);
    ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
    return {text, ntohs(v6->sin6_port)};
  }
  return {};
}

int millis_until(Clock::time_point t) {
  const auto left = std::chrono::ceil<std::chrono::milliseconds>(t - Clock::now()).count();
  return left <= 0 ? 0 : static_cast<int>(std::min<long long>(left, 60'000));
}

bool poll_for(int socket, short events, int timeout_ms) {
  pollfd p{socket, events, 0};
  int r;
  do r = ::poll(&p, 1, timeout_ms);
  while (r < 0 && errno == EINTR);
  return r > 0;
}

// One request's stream: reads end at the request's deadline and after `max_head_bytes`
// while the head is being read; writes wait at most the server's write timeout.
class GuardedStream final : public httplib::Stream {
 public:
  GuardedStream(int socket, Clock::time_point deadline, std::chrono::milliseconds write_timeout,
                std::size_t max_head_bytes)
      : socket_(socket),
        deadline_(deadline),
        write_timeout_ms_(static_cast<int>(write_timeout.count())),
        max_head_bytes_(max_head_bytes) {}

  bool is_readable() const override {
    return buffered_ < filled_ || poll_for(socket_, POLLIN, millis_until(deadline_));
  }
  bool is_writable() const override { return poll_for(socket_, POLLOUT, write_timeout_ms_); }

  ssize_t read(char* ptr, std::size_t size) override {
    if (buffered_ == filled_) {
      if (Clock::now() >= deadline_) {
        cut_off_ = true;
        return -1;
      }
      // is_readable() waits until the request's deadline at most: no byte by then (or an
      // error) ends the request, and the connection after it.
      if (!is_readable()) {
        cut_off_ = true;
        return -1;
      }
      // The head is read a byte at a time by httplib: a buffer saves a syscall per byte.
      const ssize_t n = ::recv(socket_, buffer_.data(), buffer_.size(), 0);
      if (n <= 0) return n;
      buffered_ = 0;
      filled_ = static_cast<std::size_t>(n);
      head_bytes_ += static_cast<std::size_t>(n);
      if (!head_done() && head_bytes_ > max_head_bytes_ + buffer_.size()) {
        cut_off_ = true;
        return -1;
      }
    }
    const std::size_t n = std::min(size, filled_ - buffered_);
    std::copy_n(buffer_.data() + buffered_, n, ptr);
    buffered_ += n;
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, std::size_t size) override {
    if (!is_writable()) return -1;
    return ::send(socket_, ptr, size, MSG_NOSIGNAL);
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    Endpoint e = endpoint_of(socket_, true);
    ip = std::move(e.address);
    port = e.port;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    Endpoint e = endpoint_of(socket_, false);
    ip = std::move(e.address);
    port = e.port;
  }
  socket_t socket() const override { return socket_; }

  // Once routing starts (the table says so), the head limit no longer applies: the body has
  // the server's own payload limit.
  bool head_done() const { return head_done_; }
  void set_head_done() { head_done_ = true; }
  // The request ran out of time or head bytes: the connection is closed after it (what
  // follows on it would be the rest of that request, not a new one).
  bool cut_off() const { return cut_off_; }

 private:
  int socket_;
  Clock::time_point deadline_;
  int write_timeout_ms_;
  std::size_t max_head_bytes_;
  std::array<char, 4096> buffer_{};
  std::size_t buffered_ = 0, filled_ = 0, head_bytes_ = 0;
  bool head_done_ = false;
  bool cut_off_ = false;
};

}  // namespace

void ConnectionTable::open(int socket, const std::string& address) {
  std::lock_guard lock(mutex_);
  std::size_t from_address = 0;
  for (const auto& [s, e] : entries_) from_address += e.address == address;
  if (from_address >= limits_.max_connections_per_address) evict_oldest_idle(&address);
  if (entries_.size() >= limits_.max_connections) evict_oldest_idle(nullptr);
  entries_[socket] = Entry{address, "", Phase::waiting, Clock::now()};
}

void ConnectionTable::evict_oldest_idle(const std::string* address) {
  auto oldest = entries_.end();
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    const Entry& e = it->second;
    if (e.phase != Phase::waiting && e.phase != Phase::reading) continue;
    if (address && e.address != *address) continue;
    if (oldest == entries_.end() || e.since < oldest->second.since) oldest = it;
  }
  if (oldest == entries_.end()) return;  // every one is being answered: none is idle
  // Wakes its thread (poll and recv return); that thread closes the socket and leaves the
  // table, under this mutex, so the descriptor is not reused before this call.
  ::shutdown(oldest->first, SHUT_RDWR);
  oldest->second.phase = Phase::handling;  // not chosen twice
  ++evicted_;
}

void ConnectionTable::close_idle() {
  std::lock_guard lock(mutex_);
  for (auto& [socket, e] : entries_)
    if (e.phase == Phase::waiting || e.phase == Phase::reading) ::shutdown(socket, SHUT_RDWR);
}

void ConnectionTable::close(int socket) {
  std::lock_guard lock(mutex_);
  entries_.erase(socket);
}

void ConnectionTable::set_phase(int socket, Phase phase) {
  std::lock_guard lock(mutex_);
  auto it = entries_.find(socket);
  if (it == entries_.end()) return;
  it->second.phase = phase;
  it->second.since = Clock::now();
}

std::optional<std::string> ConnectionTable::begin_stream(int socket, const std::string& client) {
  std::lock_guard lock(mutex_);
  std::size_t streams = 0, of_client = 0;
  for (const auto& [s, e] : entries_) {
    if (e.phase != Phase::streaming) continue;
    ++streams;
    of_client += e.client == client;
  }
  if (streams >= limits_.max_event_streams)
    return fmt::format("{} event streams are open, the most this server serves: close another dashboard tab "
                       "(GET /api/v1/state still answers)",
                       limits_.max_event_streams);
  if (of_client >= limits_.max_event_streams_per_client)
    return fmt::format("this page already has {} event streams open, the most allowed for one page",
                       limits_.max_event_streams_per_client);
  auto it = entries_.find(socket);
  if (it != entries_.end()) {
    it->second.phase = Phase::streaming;
    it->second.client = client;
    it->second.since = Clock::now();
  }
  return std::nullopt;
}

ConnectionCounts ConnectionTable::counts() const {
  std::lock_guard lock(mutex_);
  ConnectionCounts c;
  c.connections = entries_.size();
  for (const auto& [s, e] : entries_) c.streams += e.phase == Phase::streaming;
  c.evicted = evicted_;
  return c;
}

GuardedServer::GuardedServer(ConnectionLimits limits) : table_(limits) {}

int GuardedServer::current_socket() { return current_connection; }

bool GuardedServer::process_and_close_socket(socket_t sock) {
  table_.open(sock, endpoint_of(sock, true).address);
  current_connection = sock;
  const auto write_timeout =
      std::chrono::seconds(write_timeout_sec_) + std::chrono::microseconds(write_timeout_usec_);
  const int keep_alive_ms = static_cast<int>(keep_alive_timeout_sec_ * 1000);
  bool ok = false;
  for (std::size_t left = keep_alive_max_count_; left > 0 && svr_sock_ != INVALID_SOCKET; --left) {
    table_.set_phase(sock, ConnectionTable::Phase::waiting);
    // Wait for the next request in slices, so that a stopping server is noticed.
    bool readable = false;
    for (int waited = 0; waited < keep_alive_ms && svr_sock_ != INVALID_SOCKET && !readable; waited += 100)
      readable = poll_for(sock, POLLIN, std::min(100, keep_alive_ms - waited));
    if (!readable) break;
    table_.set_phase(sock, ConnectionTable::Phase::reading);
    GuardedStream stream(sock, Clock::now() + table_.limits().request_time,
                         std::chrono::duration_cast<std::chrono::milliseconds>(write_timeout),
                         table_.limits().max_head_bytes);
    bool closed = false;
    ok = process_request(stream, left == 1, closed, [&](httplib::Request& request) {
      stream.set_head_done();
      table_.set_phase(sock, ConnectionTable::Phase::handling);
      // Several ranges of one file are never needed by the page, and each is a copy of it
      // in the answer (40 ranges of a 1.5 MB file made 59 MB): the whole file is served
      // instead, as HTTP allows a server to ignore Range. One range is honoured.
      if (request.ranges.size() > 1) request.ranges.clear();
    });
    if (!ok || closed || stream.cut_off()) break;
  }
  current_connection = -1;
  // Out of the table first (under its mutex), so an eviction never shuts a reused number.
  table_.close(sock);
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return ok;
}

void ConnectionThreads::enqueue(std::function<void()> fn) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return running_ < hard_limit_; });
  ++running_;
  std::thread([this, fn = std::move(fn)]() mutable { run(std::move(fn)); }).detach();
}

void ConnectionThreads::run(std::function<void()> fn) {
  fn();
  fn = nullptr;  // before the count says this thread is done with the server
  std::lock_guard lock(mutex_);
  --running_;
  changed_.notify_all();
}

void ConnectionThreads::shutdown() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return running_ == 0; });
}

}  // namespace armctl::web

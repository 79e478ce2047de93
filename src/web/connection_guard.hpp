// What keeps `armctl serve` answering STOP whatever other clients do (docs/http-api.md
// "Limits"). httplib serves each connection on one thread for as long as it is open: with
// its pool of 16 threads, 16 event streams (dashboard tabs) or 40 connections sending one
// header line every 2 s left no thread for STOP. Here:
//   - every connection gets a thread of its own (ConnectionThreads), so nothing queues
//     behind a slow client;
//   - a request must arrive whole within `request_time` of its first byte and its head
//     within `max_head_bytes` (a slowloris is cut off, whatever its pace);
//   - connections are bounded in total and per client address: a new connection beyond a
//     bound closes the one that has been waiting or sending its request the longest, so a
//     new STOP always finds a thread, and a flood cannot hold the server;
//   - event streams have a budget of their own, in total and per page (client id).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "web/connection_limits.hpp"
#include "web/httplib.hpp"

namespace armctl::web {

// The open connections and what each is doing; thread-safe.
class ConnectionTable {
 public:
  enum class Phase { waiting, reading, handling, streaming };
  explicit ConnectionTable(ConnectionLimits limits) : limits_(limits) {}

  // Registers a connection, first closing (shutdown) the longest waiting or reading one of
  // the same address or of all when a bound is reached.
  void open(int socket, const std::string& address);
  void close(int socket);
  // Closes (shutdown) every connection that waits for or sends a request: a stopping server
  // does not wait for them.
  void close_idle();
  void set_phase(int socket, Phase phase);
  // Takes one of the event-stream budget for `client` (the connection becomes streaming),
  // or says why not (the refusal's text for the page).
  std::optional<std::string> begin_stream(int socket, const std::string& client);
  ConnectionCounts counts() const;
  const ConnectionLimits& limits() const { return limits_; }

 private:
  struct Entry {
    std::string address;
    std::string client;  // for streams
    Phase phase = Phase::waiting;
    std::chrono::steady_clock::time_point since;
  };
  void evict_oldest_idle(const std::string* address);  // mutex_ held

  const ConnectionLimits limits_;
  mutable std::mutex mutex_;
  std::map<int, Entry> entries_;
  std::size_t evicted_ = 0;
};

// httplib's server with the guard: each request is read through a stream with the request
// time and head size limits, its connection tracked in the table.
class GuardedServer : public httplib::Server {
 public:
  explicit GuardedServer(ConnectionLimits limits);
  ConnectionTable& connections() { return table_; }

  // The connection the calling handler thread serves (-1 outside a handler).
  static int current_socket();

 private:
  bool process_and_close_socket(socket_t sock) override;

  ConnectionTable table_;
};

// httplib's task queue: a thread for every connection (instead of a fixed pool), joined at
// shutdown. The table above bounds how many are open; `hard_limit` is the last resort
// beyond which new connections wait for a thread.
class ConnectionThreads : public httplib::TaskQueue {
 public:
  explicit ConnectionThreads(std::size_t hard_limit) : hard_limit_(hard_limit) {}
  ~ConnectionThreads() override { shutdown(); }
  void enqueue(std::function<void()> fn) override;
  void shutdown() override;

 private:
  void run(std::function<void()> fn);

  const std::size_t hard_limit_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::size_t running_ = 0;
};

}  // namespace armctl::web

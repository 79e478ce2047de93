// Serves a simulated joint bus (any JointBusLink on simulated time, normally a SimArm's
// SimBus) on a unix socket with the sim link protocol, running simulated time in step with
// the wall clock (held while a transaction waits for the master: see hold_) so that a
// master in another process sees a bus that behaves like a real one. One master at a time; a master that disconnects (or breaks the protocol) has its
// select lines lowered, and the next one may connect. Used by `armctl sim scara`.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "core/clock.hpp"
#include "devices/joint_bus/sim_link_protocol.hpp"
#include "transport/joint_bus_link.hpp"
#include "transport/serve_loop.hpp"

namespace armctl::joint_bus {

struct SimLinkServerStats {
  std::uint64_t clients = 0;          // connections accepted
  std::uint64_t protocol_errors = 0;  // clients dropped for a bad message
  std::uint64_t bytes_to_master = 0;
  std::uint64_t bytes_from_master = 0;
};

class SimLinkServer {
 public:
  // Listens on `socket_path` (a stale socket file is replaced). Throws ArmctlError.
  SimLinkServer(transport::JointBusLink& bus, std::string socket_path);
  ~SimLinkServer();  // closes and removes the socket file
  SimLinkServer(const SimLinkServer&) = delete;
  SimLinkServer& operator=(const SimLinkServer&) = delete;

  // Serves until request_stop() (async-signal-safe, any thread: wakes the loop at once).
  void run();
  void request_stop() { loop_.request_stop(); }

  const std::string& path() const { return path_; }
  const SimLinkServerStats& stats() const { return stats_; }
  // Called with one line per notable event (connect, disconnect, refused message).
  void set_log(std::function<void(const std::string&)> log) { log_ = std::move(log); }
  // Called after simulated time was advanced each millisecond. For SimBus, pass its sync():
  // it advances idle joints now instead of in one long catch-up when they are next
  // selected, which would stall a real-time master past its timeouts.
  void set_tick(std::function<void()> tick) { tick_ = std::move(tick); }

 private:
  void accept_client();
  void drop_client(const std::string& why);
  void handle_client_bytes();
  bool handle(const sim_link::Message& m);  // false: the client broke the protocol
  void refuse(const std::string& why);
  void forward_received(TimePoint sim_until);

  transport::JointBusLink& bus_;
  std::string path_;
  int listen_fd_ = -1;
  int client_fd_ = -1;
  sim_link::Parser parser_;
  SteadyClock wall_;
  transport::ServeLoop loop_;
  // Pacing hold: while a select line is high, simulated time never runs more than hold_
  // past the master's last message. A master behind a socket cannot answer within a
  // joint's abandon timeout (2.7 ms at 115200) reliably; this models one that can.
  Duration hold_{};
  TimePoint last_master_sim_{};
  int selected_ = 0;  // bit j set: select line j is high
  SimLinkServerStats stats_;
  std::function<void(const std::string&)> log_;
  std::function<void()> tick_;
};

}  // namespace armctl::joint_bus

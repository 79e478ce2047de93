// A JointBusLink to a simulated arm running in another process (`armctl sim scara`),
// over the sim link protocol (sim_link_protocol.hpp). Real (steady) clock: the arm runs
// paced to the wall clock, so the master's timeouts need a turnaround that covers the
// socket round trip (see docs/joint-bus-master.md).
#pragma once

#include <deque>
#include <string>

#include "devices/joint_bus/sim_link_protocol.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::joint_bus {

class SimLinkClient final : public transport::JointBusLink {
 public:
  // Connects and waits for the arm's hello. Throws ArmctlError (io, timeout, protocol).
  explicit SimLinkClient(const std::string& socket_path);
  ~SimLinkClient() override;
  SimLinkClient(const SimLinkClient&) = delete;
  SimLinkClient& operator=(const SimLinkClient&) = delete;

  int joint_count() const override { return joints_; }
  void set_select(int joint, bool high) override;
  void write(std::span<const std::uint8_t> bytes) override;
  void flush() override;
  std::optional<std::uint8_t> read_byte(TimePoint deadline) override;
  std::size_t drain() override;
  const Clock& clock() const override { return clock_; }
  std::uint32_t baud() const override { return baud_; }

 private:
  // Reads from the socket until `deadline` or until one message was handled; returns
  // whether a message arrived. Throws when the arm is gone or breaks the protocol.
  bool pump(TimePoint deadline);
  // The arm broke the protocol: after that nothing it sends can be trusted to line up, so
  // the link is closed (later calls fail with io) and `message` thrown as a protocol error.
  [[noreturn]] void close_for_protocol_error(const std::string& message);
  void ensure_open() const;
  void send(sim_link::Type type, std::span<const std::uint8_t> payload);

  std::string path_;
  int fd_ = -1;
  SteadyClock clock_;
  sim_link::Parser parser_;
  std::deque<std::uint8_t> rx_;
  int joints_ = 0;
  std::uint32_t baud_ = 0;
  int flushes_done_ = 0;
};

}  // namespace armctl::joint_bus

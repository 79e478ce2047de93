// The simulated joint bus: one shared UART (master TX to every joint's RX, every joint's TX
// diode-OR'ed onto the master's RX) and one select line per joint, with wire timing, a
// deterministic simulated clock, contention detection and fault injection.
//
// Timing: a byte occupies its wire for 10 bit times (8N1) from when it starts; the receiver
// gets it when its stop bit ends. Bytes queued back to back follow each other with no gap.
// Simulated time moves only inside read_byte(), flush() and run_until()/advance(): the
// whole arm (joint control ticks at 1 kHz, physics, bus transfers) runs up to that time.
//
// Contention: two joints driving TX at once (tx_enabled() or bytes overlapping on the wire)
// is counted, logged, and overlapping bytes reach the master as one corrupted byte (the
// wired-AND of the two, which is what a diode-OR of idle-high UART lines gives).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "devices/joint_sim/bus_endpoint.hpp"
#include "devices/joint_sim/fault_plan.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::joint_sim {

struct BusStats {
  std::uint64_t bytes_to_joints = 0;  // started on the master's TX
  std::uint64_t bytes_to_master = 0;  // received by the master (after faults)
  std::uint64_t contentions = 0;      // episodes of two or more joints driving TX
  std::uint64_t corrupted_bytes = 0;  // bytes garbled by contention
  std::uint64_t dropped = 0;
  std::uint64_t flipped = 0;
  std::uint64_t delayed = 0;
  std::uint64_t garbage_bytes = 0;
  std::uint64_t suppressed_dead = 0;  // bytes a dead joint tried to send
  std::uint64_t wrong_number_rewrites = 0;
};

class SimBus final : public transport::JointBusLink {
 public:
  // endpoints[i] is wired to select line i+1 (nullptr: nothing on that line). Endpoints are
  // not owned and must outlive the bus. baud > 0, else ArmctlError(invalid_argument).
  // `byte_time`: how long a byte occupies the wire; zero: 10 bit times at `baud` (a UART
  // whose real rate differs from the nominal one, e.g. an AVR's, passes its own).
  SimBus(std::uint32_t baud, std::vector<BusEndpoint*> endpoints, Duration byte_time = Duration::zero());

  // transport::JointBusLink
  int joint_count() const override { return static_cast<int>(endpoints_.size()); }
  void set_select(int joint, bool high) override;
  void write(std::span<const std::uint8_t> bytes) override;
  void flush() override;
  std::optional<std::uint8_t> read_byte(TimePoint deadline) override;
  std::size_t drain() override;
  const Clock& clock() const override { return clock_; }
  std::uint32_t baud() const override { return baud_; }

  // Run the arm forward (bus transfers in flight complete as they would).
  void run_until(TimePoint t);
  void advance(Duration d) { run_until(clock_.now() + d); }
  TimePoint now() const { return clock_.now(); }
  // Bring every endpoint up to now (they are advanced lazily); call before inspecting them.
  void sync();

  Duration byte_time() const { return byte_time_; }
  bool select(int joint) const;
  bool master_tx_busy() const { return master_.busy || !master_queue_.empty(); }
  std::size_t rx_available() const { return master_rx_.size(); }
  // When the earliest byte now on a joint's TX wire ends (the master's UART then has it),
  // or TimePoint::max(): lets a co-simulated master (an emulated chip run in steps) end its
  // step exactly there instead of taking the byte up to a step late.
  TimePoint next_byte_to_master() const;

  // Every `every` of simulated time, every joint brought up to then and `watch` called (an
  // obstacle that looks at all joints at once: SimArm::set_obstacle). Empty: none.
  void set_watch(Duration every, std::function<void(TimePoint)> watch);

  // Faults: numbering of bytes restarts with each plan. clear_faults() = empty plan.
  void set_fault_plan(FaultPlan plan);
  void clear_faults() { set_fault_plan(FaultPlan{}); }

  const BusStats& stats() const { return stats_; }
  // Human-readable record of contentions and injected faults (latest 1000 kept), and an
  // optional sink that sees each line as it is logged.
  const std::deque<std::string>& log() const { return log_; }
  void set_log_sink(std::function<void(const std::string&)> sink) { log_sink_ = std::move(sink); }

 private:
  struct WireByte {
    bool busy = false;
    bool deliver = true;
    bool corrupt = false;
    std::uint8_t value = 0;
    TimePoint start;
    TimePoint end;
  };
  struct JointLine {
    BusEndpoint* endpoint = nullptr;
    bool select = false;
    TimePoint synced;       // time the endpoint was last advanced to
    WireByte tx;
    unsigned bytes_since_select = 0;  // for the wrong-number fault (READY is bytes 0 and 1)
  };

  TimePoint next_event_time() const;
  void process_events_at(TimePoint t);
  void bring_to(JointLine& line, TimePoint t);
  void start_master_byte(TimePoint t);
  void poll_joint_tx(int index, TimePoint t);
  void check_tx_contention(TimePoint t);
  void log(TimePoint t, const std::string& line);
  void check_joint(int joint, const char* what) const;

  std::uint32_t baud_;
  Duration byte_time_;
  SimClock clock_;
  std::vector<JointLine> lines_;
  std::vector<BusEndpoint*> endpoints_;
  std::deque<std::uint8_t> master_queue_;
  WireByte master_;
  std::deque<std::uint8_t> master_rx_;
  std::vector<FaultPlan::Garbage> garbage_;  // pending, sorted by time
  FaultInjector faults_;
  BusStats stats_;
  bool in_contention_ = false;
  std::vector<bool> touched_;  // scratch for process_events_at()
  std::deque<std::string> log_;
  std::function<void(const std::string&)> log_sink_;
  std::function<void(TimePoint)> watch_;
  Duration watch_every_{};
  TimePoint next_watch_ = TimePoint::max();
};

}  // namespace armctl::joint_sim

// The joint bus master: performs transactions (spec "One transaction") with one joint or
// with every joint over any transport::JointBusLink — simulated bus, serial port + GPIO
// select lines, or a remote simulated arm. It never waits without a deadline, drains stale
// bytes before each transaction, never uses bytes it did not receive, and reports results
// per joint so that a dead joint never blanks the others.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "devices/joint_bus/bus_failure.hpp"
#include "devices/joint_bus/bus_timing.hpp"
#include "devices/joint_bus/joint_diagnostics.hpp"
#include "devices/joint_bus/status_dialect.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::joint_bus {

struct MasterOptions {
  Dialect dialect = Dialect::standard;
  BusTiming timing{};
  // Extra attempts after a failed transaction, only where repeating is safe: never for
  // drive_dist/drive_dist_max once their COMMAND word may have reached the joint, and
  // never after an answer that would repeat (930, 940).
  int retries = 0;
  // Follow each drive command with get_target and report a mismatch as verify_mismatch.
  bool verify = false;
  // drive_dist_max verification: the joint's position at the command lies between two
  // position reads; this widens that bracket (clicks) for joints that move back and forth.
  int verify_position_tolerance = 0;
};

struct MasterCounters {
  std::uint64_t transactions = 0;   // attempts, including retries
  std::uint64_t retries = 0;
  std::uint64_t failures = 0;       // failed attempts
  std::uint64_t drained_bytes = 0;  // stale bytes discarded
};

template <typename T>
struct JointOutcome {
  int joint;
  Result<T> result;
};

template <typename T>
using PerJoint = std::vector<JointOutcome<T>>;

// The three drive commands, for operations that take one of them.
enum class Drive : std::int16_t { dist = 10, dist_max = 11, to = 12 };

class BusMaster {
 public:
  explicit BusMaster(transport::JointBusLink& link, MasterOptions options = {});

  int joint_count() const { return link_.joint_count(); }
  const MasterOptions& options() const { return options_; }
  const MasterCounters& counters() const { return counters_; }
  const Clock& clock() const { return link_.clock(); }

  // Lets time pass until `until` without a transaction (on simulated links this advances
  // the arm); stray bytes that arrive meanwhile are discarded and counted.
  void idle_until(TimePoint until);

  // One command with one joint (1..joint_count()).
  Result<std::int16_t> ping(int joint, std::int16_t value);
  Status home(int joint);
  Status set_pid_state(int joint, bool on);
  Result<std::int16_t> get_position(int joint);
  Result<std::int16_t> get_target(int joint);
  Result<std::int16_t> get_joint_number(int joint);
  Status drive_dist(int joint, std::int16_t distance);
  Status drive_dist_max(int joint, std::int16_t distance);
  Status drive_to(int joint, std::int16_t position);
  Status drive(Drive kind, int joint, std::int16_t value);
  Status set_speed(int joint, std::int16_t speed);
  Status set_zone(int joint, std::int16_t zone);
  Result<bool> check_target_reached(int joint);
  // Extensions (codes 40, 41; the original firmware answers them as unknown).
  Result<std::int16_t> read_diagnostic(int joint, std::int16_t index);
  Status clear_faults(int joint);
  // Every diagnostic word of a joint (diagnostic_count transactions).
  Result<JointDiagnostics> read_diagnostics(int joint);

  // The same operation on every joint, in joint order; one result per joint.
  template <typename T>
  PerJoint<T> for_each_joint(const std::function<Result<T>(int joint)>& op) {
    PerJoint<T> out;
    out.reserve(static_cast<std::size_t>(joint_count()));
    for (int j = 1; j <= joint_count(); ++j) out.push_back(JointOutcome<T>{j, op(j)});
    return out;
  }

  // Drives every joint with its own value (values.size() == joint_count()). All drive
  // commands go out back to back, so the joints start as close together as the bus
  // allows; verification (if on) follows once every joint has been told.
  PerJoint<Ok> drive_all(Drive kind, std::span<const std::int16_t> values);

  // One raw transaction, no retries, no verification: the COMMAND code is sent as given
  // (unknown codes included: the joint answers 930 and reads no DATA). Returns the
  // RESPONSE word for commands that return one.
  Result<std::optional<std::int16_t>> transact(int joint, std::int16_t command,
                                                  std::optional<std::int16_t> data);

 private:
  struct Reading {  // what verify-after-write needs to know before a drive command
    std::optional<std::int16_t> target_before;
    std::optional<std::int16_t> position_before;
  };

  // One attempt; an ArmctlError from the link becomes a FailureKind::link error.
  Result<std::optional<std::int16_t>> attempt(int joint, std::int16_t command,
                                              std::optional<std::int16_t> data);
  Result<std::optional<std::int16_t>> exchange(int joint, std::int16_t command,
                                               std::optional<std::int16_t> data);
  Result<std::optional<std::int16_t>> with_retries(int joint, std::int16_t command,
                                                      std::optional<std::int16_t> data);
  Status command_only(int joint, std::int16_t command, std::optional<std::int16_t> data);
  Result<std::int16_t> query(int joint, std::int16_t command);
  Result<Reading> read_before_drive(Drive kind, int joint);
  Status verify_drive(Drive kind, int joint, std::int16_t value, const Reading& before);

  std::optional<std::int16_t> read_word(TimePoint deadline);
  void abandon(int joint);  // select low, then settle()
  void settle();            // discard bytes until the bus has been quiet for a while
  Error fail(FailureKind kind, Stage stage, int joint, bool command_sent,
                    std::optional<std::int16_t> status, std::string message);
  Duration word_timeout() const;

  transport::JointBusLink& link_;
  MasterOptions options_;
  MasterCounters counters_;
};

const char* command_name(std::int16_t command);  // "get_position"; "unknown" otherwise

}  // namespace armctl::joint_bus

// The arm controller's arm backend: seven joints on the joint bus, driven through the
// BusMaster, as an rc_board::ArmBackend, so the generic Board (request validation, action
// groups, notifications) speaks Robot Commands for the SCARA arm exactly as it does for the
// emulated xArm. Mapping and methods: docs/arm-controller.md.
//
// Bus work is scheduled, not done inside the Robot Commands calls: a move queues speed and
// drive commands with the instants they must take effect (sync_plan.hpp), and service()
// performs one bus transaction at a time — a due command, else the next position poll
// (joints polled round robin, continuously: ServoPositionRead answers from these readings).
// Single-threaded; time is the bus link's clock (SimClock on the simulated bus, so tests
// are deterministic).
//
// Joint faults (no answer, wrong joint number, garbage/bad STATUS, refused data) are
// logged and counted per joint, never turned into motion: a move naming a joint that is
// not answering is refused whole; a failed poll never replaces the last good reading.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "devices/arm_controller/controller_config.hpp"
#include "devices/joint_bus/joint_motion_model.hpp"
#include "devices/arm_controller/joint_settings.hpp"
#include "devices/joint_bus/sync_plan.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/rc_board/arm_backend.hpp"

namespace armctl::arm_controller {

using rc_board::ServoId;

struct ControllerOptions {
  // Offsets and BusServoInfo limits are saved here; nothing = in memory only.
  std::optional<std::filesystem::path> state_dir;
  // Measured supply voltage (e.g. the simulated arm's motor supply); empty = the config's.
  std::function<std::uint16_t()> supply_millivolts;
  std::function<void(const std::string&)> log;
};

struct JointStatus {
  std::optional<std::int16_t> clicks;  // last good get_position
  TimePoint read_at{};
  std::uint64_t reads = 0;
  std::uint64_t faults = 0;
  bool answering = false;       // the last transaction with this joint succeeded
  std::string last_fault;       // the last failure's message
  bool loop_on = true;          // position loop (torque) as last commanded
  bool jogging = false;         // motor mode (continuous velocity)
  std::optional<std::int16_t> target;  // last drive_to sent (clicks)
  TimePoint arrive_at{};        // when that target is planned to be reached
  // Following: the polled position within kNotFollowingClicks of the planned setpoint.
  // When a joint stops following (or refuses a drive, as a faulted joint does), its fault
  // and diagnostic words are read once and kept here.
  bool following = true;
  std::uint16_t joint_faults = 0;  // fault_* bits it reported then (0: none, or not read)
  std::string diagnostics;         // its diagnostic line then ("" if never read)
  // Its read_diagnostic words then (word 0 = joint_faults), as JointFaultRead answers them.
  std::array<std::uint16_t, joint_bus::diagnostic_count> diagnostic_words{};
  TimePoint faults_read_at{};      // when they were last read
  std::uint16_t following_lost = 0;  // times it stopped following (saturating)
};

// How far (clicks) a polled position may be from the planned setpoint before the joint
// counts as no longer following (normal tracking stays under 300: moving_start_test).
inline constexpr int kNotFollowingClicks = 500;

struct ControllerStats {
  std::uint64_t polls = 0;
  std::uint64_t poll_failures = 0;
  std::uint64_t sweeps = 0;        // complete rounds of polls over every joint
  std::uint64_t commands = 0;      // scheduled commands sent
  std::uint64_t command_failures = 0;
  std::uint64_t moves = 0;
  std::uint64_t refused_moves = 0; // a named joint not answering
  std::uint64_t moving_starts = 0; // joints planned from a moving start (motion model)
  double max_model_gap = 0;        // clicks: largest |polled position - modelled setpoint|
  std::uint64_t following_lost = 0;       // a joint stopped following its plan
  std::uint64_t fault_reads = 0;          // ... and its faults were read (again every 250 ms
                                          // while it is off its plan without a fault)
  std::uint64_t runaway_faults = 0;       // reads that found a runaway fault
  std::uint64_t following_error_faults = 0;
};

class ArmController final : public rc_board::ArmBackend {
 public:
  // Checks every configured joint has a select line on the bus (else invalid_config) and
  // loads saved settings (io / invalid_config errors). Sends nothing yet: call start().
  // `link` must outlive the controller; the controller's bus master talks through it.
  ArmController(transport::JointBusLink& link, joint_bus::MasterOptions master_options,
                ControllerConfig config, ControllerOptions options);

  // Sends each joint its zone and polls every joint once, so positions are known before
  // the first request. Joints that do not answer are logged; they are retried by polling.
  void start();

  // ---- rc_board::ArmBackend
  std::span<const ServoId> servos() const override { return ids_; }
  rc_board::PositionRange position_range(ServoId servo) const override;
  void advance_to(TimePoint now) override;
  Result<Duration> move(std::span<const rc_board::ServoTarget> targets, Duration time,
                        TimePoint now) override;
  std::int16_t position(ServoId servo) const override;
  void torque_off(std::span<const ServoId> servos) override;
  void halt(TimePoint now) override;
  std::uint16_t battery_millivolts() const override;
  void adjust_offset(ServoId servo, std::int8_t offset) override;
  Status save_offsets(std::span<const ServoId> servos) override;
  std::int8_t offset(ServoId servo) const override;
  void set_mode(ServoId servo, rc_board::ServoMode mode, std::int16_t speed, TimePoint now) override;
  rc_board::BusServoInfoReply bus_servo_info() const override;
  Status write_bus_servo_info(const rc_board::BusServoLimits& limits) override;
  // JointFaultRead / JointFaultClear, as the Mega controller answers them
  // (docs/arm-controller.md "Joint faults"). The clear is one bus transaction, done at once.
  bool has_joint_faults() const override { return true; }
  rc::JointFaultReport joint_faults(ServoId servo) const override;
  rc::JointFaultClearReply clear_joint_faults(ServoId servo, TimePoint now) override;

  // The bus link was lost (ReconnectingLink): every pending command is dropped and every
  // joint counts as not answering (moves naming it are refused) until it answers a poll
  // again. No target is kept for later: after the link comes back nothing moves until a
  // new command.
  void link_lost();

  // ---- bus work
  // One step: a command that is due, else (if the next due command or `limit` is closer
  // than a poll takes) waiting until then, else one position poll. Returns at or after
  // min(limit, next due) only if it waited; a poll may end past `limit`.
  void service(TimePoint limit);
  std::optional<TimePoint> next_due() const;
  // Bus time one transaction is expected to take (measured, at least the wire time).
  Duration transaction_time() const { return txn_estimate_; }

  // ---- inspection (tests, CLI, logs)
  const Clock& clock() const { return link_.clock(); }
  const joint_bus::MasterCounters& bus_counters() const { return master_.counters(); }
  const ControllerConfig& config() const { return config_; }
  const JointStatus& joint_status(int joint) const { return at(joint).status; }
  const ControllerStats& stats() const { return stats_; }
  const ControllerSettings& settings() const { return settings_; }
  // Clicks a Robot Commands position maps to for this joint, with its current offset.
  std::int32_t target_clicks(ServoId servo, std::uint16_t position) const;
  // The plan of the last move (for tests and the benchmark).
  const joint_bus::SyncPlan& last_plan() const { return last_plan_; }
  TimePoint last_move_start() const { return last_move_start_; }

 private:
  enum class OpKind { loop_on, loop_off, speed, drive_to };
  struct Op {
    TimePoint due;
    std::uint64_t seq;
    int joint;
    OpKind kind;
    std::int16_t value;
  };
  struct Joint {
    ControllerJointConfig config;
    joint_bus::JointProfile profile;  // as the joint quantizes it
    joint_bus::JointMotionModel model{joint_bus::JointProfile{}};  // its setpoint, replayed from what was sent
    std::int8_t offset = 0;
    JointStatus status;
    // The last failure's kind and stage (the master's JointFailure; empty when the error had
    // none): a fault is logged when it changes, not on every repeat.
    std::optional<std::pair<joint_bus::FailureKind, joint_bus::Stage>> last_failure;
  };

  Joint& at(int joint);
  const Joint& at(int joint) const;
  void schedule(TimePoint due, int joint, OpKind kind, std::int16_t value);
  void cancel_ops(int joint);
  void run_op(const Op& op);
  void poll_next();
  void wait_until(TimePoint t);
  void note_success(Joint& j);
  void note_fault(Joint& j, const Error& f, const char* doing);
  // Reads and logs the joint's faults (once per episode of not following).
  void examine_faults(Joint& j, const std::string& why);
  void lost_following(Joint& j, const std::string& why);
  void timed(const std::function<void()>& transaction);
  void anchor_model(Joint& j, TimePoint t);
  TimePoint effect_instant() const;
  void persist();
  void log(const std::string& line) const;

  transport::JointBusLink& link_;
  joint_bus::BusMaster master_;
  ControllerConfig config_;
  ControllerOptions options_;
  std::vector<ServoId> ids_;
  std::vector<Joint> joints_;
  ControllerSettings settings_;
  std::vector<Op> ops_;  // sorted by (due, seq)
  std::uint64_t next_seq_ = 0;
  std::size_t poll_index_ = 0;
  Duration txn_estimate_{};
  Duration min_txn_{};
  ControllerStats stats_;
  joint_bus::SyncPlan last_plan_;
  TimePoint last_move_start_{};
  TimePoint now_{};
};

}  // namespace armctl::arm_controller

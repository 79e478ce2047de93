// The arm controller's core on the board side, portable (C++14, no STL, no heap, no
// exceptions; floating point only in the main loop, never in an interrupt handler): Robot
// Commands requests in, joint bus transactions out, one at a time, never blocking.
// The Mega firmware (firmware/mega/) runs it over its UARTs; tests run it on the host.
//
// Requests (spec robot-commands.md; a frame that is malformed, names a joint that is not
// configured or a position outside its soft limits is ignored whole, as the spec says):
//   MultiServoMove     a synchronized move: every named joint arrives at the same instant
//                      (plan_move below); refused whole if a named joint is not answering
//   ServoPositionRead  answered from the latest polled positions
//   MultiServoOff      position loops off (set_pid_state 0)
//   GroupStop          every joint brought to rest (set_speed 0), notification CMD 7
//   GetBatteryVoltage  the value the board measured (set_battery_millivolts)
//   GroupDownload      sub 1..5 as docs/action-groups.md decides, into a GroupStore; a
//                      download that does not fit is refused at sub 2 (no reply, as for
//                      anything inconsistent); sub 4 and 5 are acknowledged once written
//   GroupRun/Erase/Speed  playback (each action one synchronized move), notifications
//                      CMD 6 started, 7 stopped, 8 finished; erase replies CMD 8 once written
//   ServoOffsetAdjust/Read  a zero offset per joint in position units (-125..125): targets
//                      are map(position + offset); ServoOffsetWrite keeps it in the group
//                      memory's settings record (servo_settings.cpp), loaded at begin()
//   BusServoInfoWrite/Read  address one joint (the last written; joint 1 at start): its
//                      position limits narrow what a move may ask, the voltage, temperature
//                      and LED fields are kept; persisted with the offset
//   ServoSpeed         motor mode: a velocity jog (set_speed ceil(|speed| / 10) %) toward
//                      the soft limit in that direction; servo mode (or a move) ends it
//   JointFaultRead     (CMD 40, an armctl extension) one joint's fault state: a joint that
//                      stops following its plan has its 7 read_diagnostic words read
//   JointFaultClear    (CMD 41, an armctl extension) clear_faults sent to one joint (its
//                      move stopped first), answered with the joint's STATUS
// Between commands the joints are polled round robin (get_position), so positions are
// fresh and a joint that stops answering is known before a move names it.
//
// Bus work is a queue of operations with the instant each is due; poll() starts the next
// due one, else the next position poll. A move is planned (its operations queued) by poll()
// between two transactions, never while a joint waits mid-transaction: planning seven
// joints in floating point takes the Mega several milliseconds. Time is a free-running microsecond counter that
// wraps (all comparisons are by difference).
#pragma once

#include <stdint.h>

#include "portable_controller/bus_master.hpp"
#include "portable_controller/group_store.hpp"
#include "portable_controller/ramp_model.hpp"

namespace armctl {
namespace controller {

// One joint as the arm controller sees it (the arm_controller section of config/scara.arm.json has the same values).
struct JointSetup {
  uint8_t number;          // 1..7: servo ID upstream = select line on the bus
  int16_t clicks_at_0;     // Robot Commands position 0 -> clicks
  int16_t clicks_at_1000;  // position 1000 -> clicks (a straight line between)
  int16_t soft_min;        // clicks; a target outside is refused
  int16_t soft_max;
  uint16_t max_speed_cps;   // the joint's velocity at set_speed 100 % (the arm files: 1..50,000)
  uint32_t max_accel_cps2;  // its setpoint acceleration limit (3,906..1,000,000)
  int16_t zone;             // clicks, sent with set_zone at start
};

class UpstreamPort {
 public:
  virtual void send_frame(uint8_t command, const uint8_t* data, uint8_t length) = 0;
 protected:
  ~UpstreamPort() {}
};

// A command that took effect on a joint, waiting to be folded into its model.
struct ModelEvent {
  uint32_t at_us;
  int16_t value;  // clicks (drive, rest) or percent (speed)
  uint8_t kind;   // ModelEventKind
};
enum ModelEventKind : uint8_t { model_drive, model_speed, model_rest };
static const uint8_t model_unknown_percent = 0xFF;

struct JointState {
  int16_t clicks;     // last good get_position
  uint32_t read_us;   // when the joint answered it (its RESPONSE)
  int16_t position;   // the same in Robot Commands units (to_position)
  bool read;          // clicks holds a reading
  bool answering;     // the last transaction with the joint worked
  bool loop_on;       // as last commanded
  uint16_t reads;     // saturating counters
  uint16_t faults;
  int16_t last_fault; // STATUS of the last failure (990 no answer, 910, 940, ...)
  // The joint's last planned motion: from `plan_from` (drive taking effect at
  // plan_start_us) to `plan_to`, arriving at plan_end_us (what the fault checks compare
  // its polls with). Where a new move starts is the model below, not the last poll, which
  // is up to a sweep old on a moving joint (streamed moves).
  bool planned;
  bool jogging;       // ServoSpeed motor mode
  int8_t offset;      // ServoOffsetAdjust (ServoOffsetWrite: persisted)
  // BusServoInfoWrite (persisted): position_min/max narrow the moves allowed; the rest is
  // kept and read back (the joints have no such sensors or LEDs).
  uint16_t position_min;
  uint16_t position_max;
  uint16_t millivolts_min;
  uint16_t millivolts_max;
  uint16_t temp_max;
  uint8_t led_status;
  uint8_t led_warning;
  int16_t plan_from;
  int16_t plan_to;
  uint32_t plan_start_us;
  uint32_t plan_end_us;
  int16_t plan_seen;    // its last polled position when the plan was made
  uint16_t plan_slack;  // clicks a joint still moving when planned may be off its plan's line
  // Its own faults (docs/mega-controller.md "Joint faults"): a joint that leaves its plan
  // (or refuses a drive with 940, what a faulted joint answers) is not `following`, and its
  // read_diagnostic words are read (again every 250 ms while it stays off its plan with no
  // fault held).
  bool following;
  bool diagnostics_read;        // diagnostics[] holds a complete read since it stopped following
  uint16_t diagnostics[7];      // read_diagnostic 0..6: faults, bus events lost, encoder
                                // edges lost, UART errors, reset cause, abandoned, settings
  uint16_t following_lost;      // times it stopped following (saturating)
  uint32_t faults_read_us;      // when the last read was started
  // The setpoint ramp of a move started at rest (check_ramp): armed when its drive_to
  // went out; `ramp_percent` the slower of the move's speeds (0: no ramp check, e.g. a
  // joint still moving when the move was planned). `behind_ramp`: it fell behind that
  // ramp mid-move (a stall) and the move was stopped; until a move names it again.
  // `left_plan`: it left its move's stretch mid-move (ran away, was pushed back) and the
  // move was stopped the same way.
  bool ramp_armed;
  bool behind_ramp;
  bool left_plan;
  uint8_t ramp_percent;
  RampShape ramp;               // its ramp at ramp_percent, shaped when planned
  uint32_t ramp_start_us;       // when its drive_to was answered (the ramp began before)
  uint32_t stalled_us;          // when it was found behind its ramp or off its plan
  // Its setpoint as the controller models it (docs/mega-controller.md "Moving start"): the
  // joint's ramp from `model` at model_us, fed with every speed, drive and loop-on that
  // succeeded, at the instant it took effect. A command is noted when it succeeds (integers
  // only: a main-loop pass that takes a result stays short) and folded into the model when
  // a move is planned (floating point, the planning pass). Unknown at start, after a failure
  // and while the loop is off: then the planner takes the joint at rest where it was polled.
  bool model_known;
  bool model_resting;           // at rest (on its target, or held short) as of model_us
  uint8_t model_percent;        // the speed last set (model_unknown_percent: none known)
  uint8_t model_events;         // commands noted since the last fold
  bool model_arrives;           // (not resting) comes to rest on its target at model_rest_us
  uint32_t model_us;
  uint32_t model_rest_us;
  SetpointMotion model;
  MotionPhases phases;          // of `model`, from model_us
  ModelEvent events[4];
};

struct CoreStats {
  uint16_t frames;
  uint16_t ignored_frames;  // malformed, unknown joint, out of range, unsupported
  uint16_t moves;
  uint16_t refused_moves;   // a named joint not answering
  uint32_t polls;
  uint16_t poll_failures;
  uint16_t commands;
  uint16_t command_failures;
  uint32_t sweeps;          // complete rounds of polls over every joint
  uint16_t downloads;       // groups stored
  uint16_t download_rejected;  // inconsistent sub-commands (the download is abandoned)
  uint16_t download_too_big;   // refused at sub 2: no room in the group memory
  uint16_t actions_played;
  uint16_t actions_skipped;    // a stored action that no longer fits, or a joint not answering
  uint16_t following_lost;     // a joint stopped following its plan
  uint16_t fault_reads;        // complete reads of a joint's 7 diagnostic words
  uint16_t runaway_faults;     // reads that found a runaway fault
  uint16_t following_error_faults;  // reads that found a following-error fault
  uint16_t stalls;             // a joint behind its setpoint ramp mid-move: its move stopped
};

class ControllerCore {
 public:
  static const uint8_t max_joints = 7;
  // A move of seven joints: loop-on, speed, drive and a part-way speed switch each.
  static const uint8_t max_ops = 40;
  // A polled position this far from the joint's plan: it is not following (the daemon's
  // kNotFollowingClicks); back within half of it, it follows again.
  static const int16_t not_following_clicks = 500;
  static const uint32_t fault_recheck_us = 250000;
  // A stalled joint's words are read again (every fault_recheck_us) this long after its
  // move was stopped, until a fault shows: a runaway shows 100 to 150 ms after it begins.
  static const uint32_t stall_watch_us = 1000000;
  // After the planned end, a joint has this long to settle before it counts as not arrived.
  static const uint32_t settle_us = 500000;
  // A joint's model is taken at rest on its target this long after its planned end, if
  // nothing more was sent to it (its plan had it there by then).
  static const uint32_t settled_us = 100000;
  // A joint this much closer to its target than at its previous poll is on its way.
  static const int16_t approaching_clicks = 8;

  // `joints` (count <= 7, numbers distinct) must outlive the core. Queues set_speed 0 and
  // then set_zone for every joint: after a reset nothing keeps moving on an old command.
  // `groups`: where action groups are kept (nullptr: group requests are ignored).
  // The last `settings_bytes` of `groups` hold each joint's persisted offset and
  // BusServoInfo limits (servo_settings.cpp); groups use the rest. `directory`: room for
  // the group directory's `entries` (1..255) that outlives the core; nullptr: the core's
  // own, of GroupStore::mega_entries (the Mega's layout).
  static const uint16_t settings_bytes = 96;
  void begin(const JointSetup* joints, uint8_t count, BusPort* bus, UpstreamPort* upstream,
             uint32_t bus_baud, uint32_t now_us, GroupMemory* groups = nullptr,
             GroupStore::Entry* directory = nullptr, uint8_t entries = 0);

  void on_frame(uint8_t command, const uint8_t* data, uint8_t length, uint32_t now_us);
  void on_bus_byte(uint8_t byte, uint32_t now_us) { master_.on_rx_byte(byte, now_us); }
  // From an interrupt handler: the time comes from the bus port (BusMaster::on_rx_byte).
  void on_bus_byte(uint8_t byte) { master_.on_rx_byte(byte); }
  // Bus work: ends a timed-out transaction, takes a result, starts the next transaction.
  void poll(uint32_t now_us);

  void set_battery_millivolts(uint16_t millivolts) { battery_mv_ = millivolts; }
  // Every queued group-memory write done now, for a memory that is always ready (a file on
  // Linux, CoreDevice). The Mega's EEPROM takes 3.4 ms a byte: poll() starts one a pass.
  void flush_group_writes() {
    while (have_groups_ && !groups_.idle() && memory_->ready()) groups_.service();
  }
  // The bus link was lost (a Linux board's link that closed and reconnects; the Mega's
  // wires cannot be): playback stops (CMD 7), every queued command is dropped for set_speed
  // 0 to every joint, and every joint counts as not answering (a move naming it is refused)
  // until it answers a poll again. Nothing moves after the link returns until a new request.
  void link_lost(uint32_t now_us);

  // Position <-> clicks through the joint's line (rounded to nearest); 0 for no joint.
  int16_t to_clicks(uint8_t joint, uint16_t position) const;
  int16_t to_position(uint8_t joint, int16_t clicks) const;

  // Inspection (tests, diagnostics). joint_state(n) of an unconfigured n is all zero.
  const JointState& joint_state(uint8_t joint) const;
  const CoreStats& stats() const { return stats_; }
  uint8_t pending_ops() const { return op_count_; }
  // The speed percent the last move gave each joint (0: not in that move).
  uint8_t planned_percent(uint8_t joint) const;
  // The move's planned duration from its start, in ms.
  uint32_t planned_ms() const { return planned_ms_; }
  const BusMaster& master() const { return master_; }
  const GroupStore& groups() const { return groups_; }
  bool playing() const { return playing_; }

 private:
  // speed_switch: the part-way set_speed of a move (plan_move).
  // clear_faults: JointFaultClear's, answered upstream with its STATUS.
  enum class OpKind : uint8_t { set_zone, loop_on, loop_off, speed, drive_to, diagnostic, speed_switch, clear_faults };
  struct Op {
    uint32_t due_us;
    uint8_t joint;
    OpKind kind;
    int16_t value;
  };
  struct Target {
    uint8_t index;  // into joints_
    int16_t clicks;
  };
  enum class Check : uint8_t { ok, invalid, not_answering };
  enum class Awaiting : uint8_t { nothing, download_action, download_end, erase };

  int8_t index_of(uint8_t joint) const;
  bool schedule(uint32_t due_us, uint8_t index, OpKind kind, int16_t value);
  void cancel_ops(uint8_t index, bool drives_only);
  // Kept when a joint's commands are cancelled: reads of its diagnostic words and a
  // clear_faults (they are not motion, and a host waits for the clear's answer).
  static bool kept_through_moves(OpKind kind) { return kind == OpKind::diagnostic || kind == OpKind::clear_faults; }
  // The joint's queued op of this kind gets the new value and goes out no later than
  // either due time, keeping its place in the queue; else a new one is queued.
  bool upsert(uint32_t due_us, uint8_t index, OpKind kind, int16_t value);
  void start_next(uint32_t now_us);
  // The next poll queued behind the transaction under way (BusMaster::chain), so that it
  // starts from the STATUS itself (on the Mega: from the receive interrupt); only while
  // the bus has nothing else to do for a while: no plan or group action waiting, no
  // command due within two transactions. A queued one that no longer qualifies is dropped.
  bool may_chain_poll(uint32_t now_us) const;
  void chain_poll(uint32_t now_us);
  void take_result(const BusResult& r, uint32_t now_us);
  void handle_result(const BusResult& r, uint32_t now_us);
  // The last poll's reading converted and checked (after the next transaction started).
  void after_poll(uint32_t now_us);
  void note_fault(uint8_t index, int16_t status);
  // Joint faults: the polled `clicks` against the plan; queues a read of the 7 words.
  void check_following(uint8_t index, int16_t before, uint32_t now_us);
  // A joint of a move started at rest more than not_following_clicks behind the least its
  // setpoint ramp can have covered: stalled. Its move is stopped (stop_move). True then.
  bool check_ramp(uint8_t index, uint32_t now_us);
  // A joint of a streamed move (planned while it moved: no ramp from rest to compare with)
  // whose last poll is more than not_following_clicks from where its model had the setpoint
  // then, beyond what the model's acceleration leaves open: stalled (or run away). Checked
  // when its model is folded for the next point, so found within a point of the stream, not
  // when the stream ends; every move under way is stopped then (stop_move). True then.
  bool check_stream(uint8_t index, uint32_t now_us);
  // Either check's finding: `behind_ramp`, counted, its move (`every_move`: every move)
  // stopped and its words read. True.
  bool stalled(uint8_t index, uint32_t now_us, bool every_move);
  // Every joint of the move that `index` belongs to (same planned end) brought to rest
  // (set_speed 0), and a playing group stopped (CMD 7).
  // `every_move`: every joint under a plan instead (a stream's joints each have their own end).
  void stop_move(uint8_t index, uint32_t now_us, bool every_move = false);
  void lost_following(uint8_t index, uint32_t now_us);
  void read_diagnostics(uint8_t index, uint32_t now_us);
  void on_joint_fault_read(const uint8_t* data, uint8_t length);
  void on_joint_fault_clear(const uint8_t* data, uint8_t length, uint32_t now_us);
  // The joint's answer to clear_faults: a cleared joint follows again with no fault known
  // and holds where it is (its model unknown until a move); the STATUS goes upstream.
  void faults_cleared(uint8_t index, const BusResult& r);
  // The joint's model (see JointState): a command that took effect noted; forgotten; the
  // noted commands folded in (an unknown model anchored at rest where the joint was last
  // polled, at `now_us`), its phases shaped; anchored at rest on a spot.
  void note_model(uint8_t index, uint8_t kind, int16_t value, uint32_t at_us);
  void forget_model(uint8_t index);
  void fold_model(uint8_t index, uint32_t now_us);
  void rest_model(uint8_t index, float at, uint8_t percent, uint32_t now_us);
  // One joint of the pending move whose model has commands to fold: folded (true).
  bool fold_pending(uint32_t now_us);
  bool plan_due() const;
  // A move's set_speed for the joint: a queued one takes the new value; else one is queued
  // unless the joint already runs at that speed. Likewise its drive_to (queued at `due_us`).
  void want_speed(uint8_t index, uint8_t percent, uint32_t due_us);
  void want_drive(uint8_t index, int16_t clicks, uint32_t due_us);
  bool queued(uint8_t index, OpKind kind) const;
  bool in_flight(uint8_t index, OpKind kind) const;

  Check check_targets(const uint8_t* servos, const uint16_t* positions, uint8_t n, Target* out,
                      uint8_t* moving) const;
  void on_move(const uint8_t* data, uint8_t length);
  // Action groups (group_requests.cpp).
  void on_group_download(const uint8_t* data, uint8_t length);
  bool download_step(const uint8_t* data, uint8_t length);
  void on_group_run(const uint8_t* data, uint8_t length, uint32_t now_us);
  void on_group_erase(const uint8_t* data, uint8_t length, uint32_t now_us);
  void on_group_speed(const uint8_t* data, uint8_t length);
  void stop_playing(bool notify);
  void play_next(uint32_t now_us);
  void service_groups();
  void notify(uint8_t command, uint8_t group, uint16_t count);
  void on_position_read(const uint8_t* data, uint8_t length);
  void on_servo_off(const uint8_t* data, uint8_t length, uint32_t now_us);
  // Offsets and motor mode (servo_requests.cpp).
  int16_t target_clicks(uint8_t index, uint16_t position) const;
  void on_offset_adjust(const uint8_t* data, uint8_t length);
  void on_offset_read(const uint8_t* data, uint8_t length);
  void on_servo_speed(const uint8_t* data, uint8_t length, uint32_t now_us);
  // Persisted servo settings (servo_settings.cpp).
  void load_settings();
  void default_settings(JointState& s) const;
  uint32_t settings_at(uint8_t index) const;
  bool save_settings(uint8_t index);  // queued; false (nothing queued) if no room
  void on_offset_write(const uint8_t* data, uint8_t length);
  void on_bus_servo_info_write(const uint8_t* data, uint8_t length);
  void on_bus_servo_info_read(uint8_t length);
  void halt(uint32_t now_us);
  void plan_move(const Target* targets, uint8_t count, uint16_t time_ms, uint32_t now_us);
  // True if a move was planned; `now_or_never`: even right after another plan (a request
  // that must come after it).
  bool plan_pending(uint32_t now_us, bool now_or_never = false);
  void reply_u16(uint8_t command, uint16_t value);

  const JointSetup* joints_ = nullptr;
  uint8_t count_ = 0;
  UpstreamPort* upstream_ = nullptr;
  BusMaster master_;
  JointState state_[max_joints];
  uint8_t percent_[max_joints];
  Op ops_[max_ops];
  uint8_t op_count_ = 0;
  bool inflight_is_op_ = false;
  OpKind inflight_kind_ = OpKind::set_zone;
  int16_t inflight_value_ = 0;
  uint8_t inflight_index_ = 0;
  uint8_t poll_index_ = 0;
  // The joint whose polled clicks still wait for their conversion to position and their
  // check against its plan (after_poll), and its reading before.
  static const uint8_t no_convert = 0xFF;
  uint8_t convert_ = no_convert;
  int16_t polled_before_ = 0;
  uint8_t check_ = no_convert;  // the joint whose converted reading waits for its check
  int16_t check_before_ = 0;
  uint8_t ramp_check_ = no_convert;  // the joint whose reading waits for its ramp check
  uint16_t battery_mv_ = 0;
  uint32_t planned_ms_ = 0;
  CoreStats stats_{};
  // A move accepted but not yet planned: it is planned between two transactions.
  Target pending_[max_joints];
  uint8_t pending_count_ = 0;
  uint16_t pending_ms_ = 0;
  static const uint8_t min_txns_between_plans = 4;
  uint8_t txns_since_plan_ = 255;  // commands started since the last plan
  uint32_t last_now_us_ = 0;        // poll()'s time
  static const uint8_t max_commands_in_row = 3;
  uint8_t commands_in_row_ = 0;     // commands started since the last poll

  GroupStore groups_;
  GroupStore::Entry directory_[GroupStore::mega_entries];
  bool have_groups_ = false;
  GroupMemory* memory_ = nullptr;
  uint8_t info_index_ = 0;  // the joint BusServoInfoWrite/Read address
  Awaiting awaiting_ = Awaiting::nothing;
  // The download in progress (docs/action-groups.md): stage = last sub accepted.
  uint8_t download_stage_ = 0;
  uint8_t download_group_ = 0;
  uint16_t download_count_ = 0;
  uint8_t download_servos_ = 0;
  uint32_t download_start_ = 0;
  uint8_t download_got_[1020 / 8 + 1];  // one bit per action slot
  // Playback.
  bool playing_ = false;
  GroupInfo play_{};
  uint16_t play_count_ = 0;  // passes asked, 0 = until stopped
  uint16_t play_pass_ = 0;
  uint16_t play_index_ = 0;
  uint32_t play_due_us_ = 0;
  uint16_t speeds_[255];     // percent per group, 100 = as recorded (volatile)
};

}  // namespace controller
}  // namespace armctl

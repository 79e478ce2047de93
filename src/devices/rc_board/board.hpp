// The board side of Robot Commands: bytes or frames in, replies and notifications out,
// over an ArmBackend (the emulated xArm's six bus servos). armctl's extensions CMD 40 and
// 41 (joint faults) are unknown commands here, as on an xArm.
//
// Every request is validated before anything happens (spec "Decisions"): an unknown CMD,
// a DATA length that disagrees with its count, a servo the arm does not have, or a value
// out of range makes the board ignore the whole frame (no partial effect, no reply); the
// frame is counted in stats() and described in last_rejection().
//
// Single-threaded and clock-driven: call receive()/handle() when bytes arrive and poll()
// whenever the clock reaches next_wakeup() (group playback). With a SimClock, tests
// advance time and call poll().
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "core/clock.hpp"
#include "devices/rc_board/arm_backend.hpp"
#include "devices/rc_board/board_stats.hpp"
#include "devices/rc_board/group_download.hpp"
#include "devices/rc_board/group_player.hpp"
#include "devices/rc_board/group_store.hpp"
#include "protocol/robot_commands/frame.hpp"
#include "protocol/robot_commands/frame_receiver.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::rc_board {

class Board {
 public:
  using Output = std::function<void(const rc::Frame&)>;
  using Log = std::function<void(const std::string&)>;

  // All references must outlive the Board. `output` receives each reply/notification.
  Board(ArmBackend& arm, GroupStore& store, const Clock& clock, Output output);

  // Wire bytes (serial form); complete frames are handled at once.
  void receive(std::span<const std::uint8_t> bytes);
  // One frame (e.g. from a HID report).
  void handle(const rc::Frame& frame);
  // Advances the arm and group playback to clock.now().
  void poll();
  // When poll() must next run for playback to keep its timing (nothing while idle).
  std::optional<TimePoint> next_wakeup() const { return player_.next_event(); }

  // Ends a running group without a GroupStop from the host (the arm lost its joints, say):
  // the host is sent the "stopped" notification and `why` is logged. Nothing if idle.
  void stop_playback(const std::string& why);

  // Rejected frames and storage problems are described here too (e.g. to stderr).
  void set_log(Log log) { log_ = std::move(log); }

  BoardStats stats() const;
  const std::string& last_rejection() const { return last_rejection_; }
  std::optional<GroupNumber> running_group() const { return player_.group(); }
  bool download_in_progress() const { return download_.in_progress(); }
  std::uint16_t group_speed(GroupNumber group) const { return speeds_[group]; }
  std::size_t group_actions_skipped() const { return player_.actions_skipped(); }
  const GroupStore& store() const { return store_; }
  const ArmBackend& arm() const { return arm_; }

 private:
  void dispatch(const rc::Frame& frame, TimePoint now);

  // One handler per request (board_requests.cpp).
  void on(const rc::MultiServoMove& m, TimePoint now);
  void on(const rc::MultiServoOff& m, TimePoint now);
  void on(const rc::ServoPositionRead& m, TimePoint now);
  void on(const rc::ServoSpeed& m, TimePoint now);
  void on(const rc::GetBatteryVoltage& m, TimePoint now);
  void on(const rc::ServoOffsetAdjust& m, TimePoint now);
  void on(const rc::ServoOffsetWrite& m, TimePoint now);
  void on(const rc::ServoOffsetRead& m, TimePoint now);
  void on(const rc::BusServoInfoWrite& m, TimePoint now);
  void on(const rc::BusServoInfoRead& m, TimePoint now);
  void on(const rc::GroupDownloadBegin& m, TimePoint now);
  void on(const rc::GroupDownloadServoCount& m, TimePoint now);
  void on(const rc::GroupDownloadBlocks& m, TimePoint now);
  void on(const rc::GroupDownloadAction& m, TimePoint now);
  void on(const rc::GroupDownloadEnd& m, TimePoint now);
  void on(const rc::GroupRun& m, TimePoint now);
  void on(const rc::GroupStop& m, TimePoint now);
  void on(const rc::GroupErase& m, TimePoint now);
  void on(const rc::GroupSpeed& m, TimePoint now);

  // Checks and replies the handlers share.
  bool all_present(std::span<const std::uint8_t> ids, const char* what);  // rejects if not
  void reply(const rc::BoardMessage& message);
  void ack(std::uint8_t sub);  // GroupDownload sub `sub` accepted
  void download_failed(const Error& e);
  void reject(std::size_t BoardStats::*counter, std::string message);
  // A read the servo bus did not answer usably (ArmBackend::read_position): no reply.
  void no_answer(const char* request, std::optional<ServoId> servo);
  void send(const rc::Frame& frame);
  void notify_stopped();
  void advance_to(TimePoint now);

  ArmBackend& arm_;
  GroupStore& store_;
  const Clock& clock_;
  Output output_;
  Log log_;
  rc::FrameReceiver receiver_;
  GroupDownload download_;
  GroupPlayer player_;
  std::uint16_t speeds_[kGroupCount + 1];
  BoardStats stats_;
  std::string last_rejection_;
  TimePoint last_now_{};
};

}  // namespace armctl::rc_board

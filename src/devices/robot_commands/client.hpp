// The Robot Commands host SDK: a typed API over any RcLink (serial, HID, in-memory).
//
// Every call validates its arguments against the client's servo range and the spec's
// ranges before anything is sent; a refused call sends nothing. Calls that have a reply
// wait for the frame with the same CMD (and, for GroupDownload, the same sub-command),
// bounded by reply_timeout. Notifications that arrive meanwhile are queued as GroupEvents
// (and passed to the callback, if set); nothing is lost. Not thread-safe: one thread uses
// one Client. Every call returns its failure (docs/architecture.md "Errors"): a link's I/O
// failure comes back as an io error, never as an exception.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "core/error.hpp"
#include "devices/robot_commands/group_event.hpp"
#include "devices/robot_commands/rc_link.hpp"
#include "protocol/robot_commands/joint_faults.hpp"
#include "protocol/robot_commands/messages.hpp"
#include "protocol/robot_commands/units.hpp"

namespace armctl::robot_commands {

using rc::BusServoInfoReply;
using rc::BusServoInfoWrite;
using rc::ServoMode;
using rc::ServoOffset;
using rc::ServoPosition;
using rc::ServoTarget;

struct ClientOptions {
  int servo_count = 6;  // 6 for the xArm, 7 for our SCARA arm controller
  Duration reply_timeout = std::chrono::milliseconds(500);
  // A GroupDownload ack can take longer on a real board (flash writes).
  Duration download_timeout = std::chrono::milliseconds(2000);
  // Reads (positions, battery, offsets, bus-servo info) are sent again when no reply came
  // within reply_timeout, up to this many attempts in all. Never anything else: a move,
  // servo-off or group command sent twice could act twice.
  int read_attempts = 1;
  // How often something that follows motion should read positions (`armctl xarm watch`,
  // the motion layer's following check). The client itself never polls. Reads during a
  // move can make real servos jerk, and HID boards answer slowly (docs/usb-hid.md).
  Duration poll_interval = std::chrono::milliseconds(200);
  // servos_off as one MultiServoOff per servo (true), or one frame for all. Real xArm
  // boards can leave some servos powered after a combined frame; only boards that are
  // ours (the emulated xArm, the arm controller) are known to handle it.
  bool servo_off_per_servo = true;
  // The wait for the reply to an armctl extension (JointFaultRead). A board without the
  // extension ignores the request, so the first one costs it this long once (then the
  // client knows and asks no more); armctl's Mega answers within a few frame times.
  Duration extension_timeout = std::chrono::milliseconds(250);
};

using rc::GroupAction;  // one action of a group (protocol/robot_commands/messages.hpp)

struct ClientStats {
  std::size_t frames_sent = 0;
  std::size_t frames_received = 0;
  std::size_t unreadable_frames = 0;  // did not decode as any board message
  std::size_t stale_replies = 0;      // a reply nobody was waiting for (e.g. after a timeout)
  std::size_t read_retries = 0;       // reads sent again after a timeout
};

class Client {
 public:
  using EventCallback = std::function<void(const GroupEvent&)>;

  // `link` must outlive the Client. Throws ArmctlError(invalid_argument) for a servo count
  // outside 1..19.
  explicit Client(RcLink& link, ClientOptions options = {});

  // ---- servos
  // Moves the listed servos over `time_ms` (0..30000). A target without a position is sent
  // as 0xFF00: that servo is left where it is.
  Status move(const std::vector<ServoTarget>& targets, std::uint16_t time_ms);
  Result<std::vector<ServoPosition>> read_positions(const std::vector<std::uint8_t>& servos);
  Result<std::vector<ServoPosition>> read_all_positions();
  // A position read in two halves, for a loop that keeps sending moves while the reply comes
  // back (a Robot Commands line is full duplex and a move has no reply): request_positions
  // sends the ServoPositionRead and returns; collect_positions returns its reply, waiting
  // for it until options.reply_timeout after the request, and if none came by then reads as
  // read_positions does (a retry). Frames that arrive meanwhile, the reply among them, are
  // handled as usual by whatever receives them (a move, pump_events, another request) and
  // the reply is kept until collected. One request at a time: a second one, and
  // read_positions, first collect the one in flight (so that its reply is never taken for
  // theirs).
  Status request_positions(const std::vector<std::uint8_t>& servos);
  Result<std::vector<ServoPosition>> collect_positions();
  bool position_request_pending() const { return pending_read_.has_value(); }
  // Removes torque (per options.servo_off_per_servo), then reads the servos' positions
  // back: replies come in order, so an answer proves the board has handled every off
  // frame. Robot Commands cannot read torque itself, so that is all that can be checked.
  Status servos_off(const std::vector<std::uint8_t>& servos);
  Result<std::uint16_t> battery_millivolts();
  Result<std::vector<ServoOffset>> read_offsets(const std::vector<std::uint8_t>& servos);
  Status adjust_offset(std::uint8_t servo, int offset);  // -125..125, lost at power-off
  Status save_offsets(const std::vector<std::uint8_t>& servos);
  // The offset each listed servo holds, as this client last read it; the servos it has not
  // read since connecting, or has since changed (adjust_offset, write_bus_servo_info), are
  // read now in one ServoOffsetRead. A servo's position read-back is its shaft, commanded +
  // offset (robot-commands.json, "BusServoInfoRead reply"), so whoever compares read-backs
  // with commanded positions subtracts these (arm/rc_arm_device.hpp). An offset another
  // program changes on the board meanwhile is not seen.
  Result<std::vector<int>> held_offsets(const std::vector<std::uint8_t>& servos);
  // ServoSpeed. `speed` is the motor-mode speed, -1000..1000 (negative = reverse; a board
  // ignores the value in servo mode); it travels as the spec's u16 in two's complement, so
  // a raw u16 such as static_cast<std::uint16_t>(-500) converts to the same speed. Values
  // outside -1000..1000 are refused before sending (a board ignores such a frame).
  Status set_mode(std::uint8_t servo, ServoMode mode, std::int16_t speed);
  Result<BusServoInfoReply> read_bus_servo_info();
  Status write_bus_servo_info(const BusServoInfoWrite& info);

  // ---- armctl extensions (a board that does not know them ignores them)
  // JointFaultRead (CMD 40, protocol/robot_commands/joint_faults.hpp): one joint's fault
  // state on armctl's arm controllers (the Mega, the daemon). std::nullopt: the board does not answer it (an
  // xArm, the xArm emulator): learnt from the first request that got no
  // reply within options.extension_timeout; from then on nothing is sent. Once a board
  // has answered, a missing reply is a timeout error as for any read.
  Result<std::optional<rc::JointFaultReport>> read_joint_faults(std::uint8_t servo);
  // JointFaultClear (CMD 41): the board sends clear_faults to the joint (it holds where
  // it is and drives again) and answers with the joint's STATUS (`cleared()`). A move the
  // joint belongs to is stopped first. std::nullopt as for read_joint_faults (the two are
  // one extension: a board that ignored one is not asked the other).
  Result<std::optional<rc::JointFaultClearReply>> clear_joint_faults(std::uint8_t servo);
  // What the client knows: true answered, false ignored, nullopt not asked yet.
  std::optional<bool> has_joint_faults() const { return has_joint_faults_; }

  // ---- action groups
  // Downloads 1..1,020 actions (all with the same number of servos) as sub-commands 1..5,
  // each acknowledged. Every frame is built and validated before the first is sent.
  Status download_group(std::uint8_t group, const std::vector<GroupAction>& actions);
  Status run_group(std::uint8_t group, std::uint16_t times);  // 0 = continuous
  Status stop_group();
  Status erase_group(std::uint8_t group);  // 255 = all
  Status set_group_speed(std::uint8_t group, std::uint16_t percent);  // 255 = all groups

  // ---- notifications
  void set_event_callback(EventCallback callback) { callback_ = std::move(callback); }
  // Queued events, oldest first (also filled when a callback is set).
  std::optional<GroupEvent> next_event();
  std::size_t pending_events() const { return events_.size(); }
  // Receives (and queues) notifications until `deadline`; returns how many arrived.
  Result<std::size_t> pump_events(TimePoint deadline);
  // The next event (queued first); a timeout error if none arrives before `deadline`.
  Result<GroupEvent> wait_event(TimePoint deadline);

  // ---- misc
  rc::ServoRange servos() const { return servos_; }
  std::vector<std::uint8_t> all_servos() const;
  const ClientStats& stats() const { return stats_; }
  RcLink& link() { return link_; }
  const ClientOptions& options() const { return options_; }
  const Clock& clock() const { return link_.clock(); }

  // Every frame download_group would send, validated, in order (for inspection/tests).
  Result<std::vector<rc::Frame>> group_download_frames(std::uint8_t group,
                                                       const std::vector<GroupAction>& actions) const;

 private:
  Result<rc::Frame> build(const rc::Request& request) const;
  Status send(const rc::Frame& frame);
  // The link's next frame; the link's ArmctlError (io) becomes the returned error.
  Result<std::optional<rc::Frame>> receive(TimePoint deadline);
  // Sends `frame` and waits for the reply with `cmd` (and `sub` for GroupDownload acks).
  Result<rc::BoardMessage> transact(const rc::Frame& frame, std::optional<std::uint8_t> sub,
                                    Duration timeout);
  // Sends `frame` and waits for a frame with the same CMD, undecoded (extensions, which
  // decode_board_message does not know); other frames are taken as usual meanwhile.
  Result<std::optional<rc::Frame>> transact_raw(const rc::Frame& frame, Duration timeout);
  // An armctl extension's request and its decoded reply for `servo`, or nothing from a
  // board that ignores the extensions (learnt from the first missing reply, then nothing is
  // sent). Instantiated in client.cpp only.
  template <typename Reply>
  Result<std::optional<Reply>> extension_request(const Result<rc::Frame>& request, const char* name,
                                                 std::uint8_t servo, Result<Reply> (*decode)(const rc::Frame&));
  // transact for a read: up to options_.read_attempts attempts while replies time out.
  // `attempts_made`: attempts already made for this read elsewhere (collect_positions).
  Result<rc::BoardMessage> transact_read(const rc::Frame& frame, int attempts_made = 0);
  Result<std::vector<ServoPosition>> read_positions_after(const std::vector<std::uint8_t>& servos,
                                                          int attempts_made);
  // The reply's servos checked against those asked for.
  Result<std::vector<ServoPosition>> positions_answering(const std::vector<std::uint8_t>& servos,
                                                         std::vector<ServoPosition> positions) const;
  // No reply to `frame` within `timeout`: the timeout error, naming the request.
  Error no_reply(const rc::Frame& frame, std::optional<std::uint8_t> sub, Duration timeout) const;
  // Takes every frame that has already arrived (queues notifications, counts late
  // replies as stale), so a late answer to an earlier request is not taken for the next.
  Status take_arrived();
  // Handles one incoming frame; returns the board message if it is a reply.
  std::optional<rc::BoardMessage> take(const rc::Frame& frame);
  void deliver(const rc::GroupNotification& n);

  RcLink& link_;
  ClientOptions options_;
  rc::ServoRange servos_;
  std::deque<GroupEvent> events_;
  EventCallback callback_;
  bool stop_sent_ = false;  // tells "stopped" from "finished" for a bare CMD 7
  std::optional<bool> has_joint_faults_;
  std::map<std::uint8_t, int> held_offsets_;  // servo -> offset, as last read (held_offsets)
  struct PendingRead {  // request_positions' request, until collected
    std::vector<std::uint8_t> servos;
    rc::Frame request;
    TimePoint deadline;
    std::optional<rc::ServoPositionReply> reply;
  };
  std::optional<PendingRead> pending_read_;
  ClientStats stats_;
};

}  // namespace armctl::robot_commands

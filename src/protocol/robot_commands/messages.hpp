// Typed Robot Commands messages: every request (host -> board), reply and notification
// (board -> host) of spec/robot-commands.md, with encoders and decoders that validate.
//
// Encoders refuse values out of range, wrong counts and servos that are not present, with
// an error naming the field and what is allowed; nothing is encoded then. Decoders turn a
// frame into exactly one message or an error: never a partial result.
#pragma once

#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

#include "core/error.hpp"
#include "protocol/robot_commands/command_codes.hpp"
#include "protocol/robot_commands/frame.hpp"

namespace armctl::rc {

// Which servo IDs a board has: first..last (xArm: 1..6; our SCARA controller: 1..7).
struct ServoRange {
  std::uint8_t first = 1;
  std::uint8_t last = 6;
  bool contains(int servo) const { return servo >= first && servo <= last; }
  int count() const { return last - first + 1; }
  static ServoRange xarm() { return {1, 6}; }
  static ServoRange of_count(int n) { return {1, static_cast<std::uint8_t>(n)}; }
};

// ---- ranges (spec "Units and ranges" and this project's decisions, docs/robot-commands.md)
constexpr std::uint16_t kPositionMin = 0;
constexpr std::uint16_t kPositionMax = 1000;
constexpr std::uint16_t kLeaveAlone = 0xFF00;  // MultiServoMove "null": servo not moved
constexpr std::uint16_t kMoveTimeMaxMs = 30000;
constexpr int kOffsetMin = -125;
constexpr int kOffsetMax = 125;
constexpr std::uint16_t kTempMaxMin = 50;
constexpr std::uint16_t kTempMaxMax = 100;
constexpr std::uint16_t kMillivoltsMin = 4500;
constexpr std::uint16_t kMillivoltsMax = 12000;
constexpr std::uint8_t kGroupMax = 254;     // groups 0..254; 255 means "all"
constexpr std::uint8_t kAllGroups = 255;
constexpr int kActionsMax = 1020;           // 4 blocks of 255
constexpr int kActionsPerBlock = 255;
constexpr int kBlocksMax = 4;
constexpr std::uint16_t kSpeedPercentMin = 1;   // 0 % would never finish
constexpr std::uint16_t kSpeedPercentMax = 1000;
constexpr std::size_t kMaxServosPerFrame = 19;  // 3 + 3 n <= 60 bytes of DATA
// ServoSpeed in motor mode: a signed speed -kMotorSpeedMax..kMotorSpeedMax (the LX bus-servo
// convention; a board ignores a frame outside it, the SDK refuses to send one).
constexpr int kMotorSpeedMax = 1000;

enum class ServoMode : std::uint8_t { servo = 0, motor = 1 };

// One entry of a move: position 0..1000, or nothing = leave this servo alone (0xFF00).
struct ServoTarget {
  std::uint8_t servo = 0;
  std::optional<std::uint16_t> position;
  bool operator==(const ServoTarget&) const = default;
};

// One action of a group: a MultiServoMove (time + positions). Here, not in the host SDK, so
// that the group files (files/action_group_file.hpp) need only the protocol.
struct GroupAction {
  std::uint16_t time_ms = 0;
  std::vector<ServoTarget> targets;
  bool operator==(const GroupAction&) const = default;
};

// ---------------------------------------------------------------- requests (host -> board)
struct MultiServoMove {
  std::uint16_t time_ms = 0;
  std::vector<ServoTarget> targets;  // 1..19 entries, each servo at most once
  bool operator==(const MultiServoMove&) const = default;
};

struct GroupDownloadBegin {  // sub 1
  std::uint8_t group = 0;
  std::uint16_t action_count = 0;  // 1..1020, on the wire a run of bytes summing to it
  bool operator==(const GroupDownloadBegin&) const = default;
};
struct GroupDownloadServoCount {  // sub 2
  std::uint8_t group = 0;
  std::uint8_t servo_count = 0;  // servos in each action, 1..servos of the board
  bool operator==(const GroupDownloadServoCount&) const = default;
};
struct GroupDownloadBlocks {  // sub 3
  std::uint8_t group = 0;
  std::uint8_t block_count = 0;  // 1..4 (blocks 0..block_count-1 in use)
  bool operator==(const GroupDownloadBlocks&) const = default;
};
struct GroupDownloadAction {  // sub 4
  std::uint8_t group = 0;
  std::uint8_t block = 0;  // 0..3
  std::uint8_t index = 0;  // 0..254 within the block
  std::uint16_t time_ms = 0;
  std::vector<ServoTarget> targets;
  bool operator==(const GroupDownloadAction&) const = default;
};
struct GroupDownloadEnd {  // sub 5
  std::uint8_t group = 0;
  bool operator==(const GroupDownloadEnd&) const = default;
};
struct GroupRun {
  std::uint8_t group = 0;
  std::uint16_t count = 1;  // 0 = continuous
  bool operator==(const GroupRun&) const = default;
};
struct GroupStop {
  bool operator==(const GroupStop&) const = default;
};
struct GroupErase {
  std::uint8_t group = 0;  // 255 = all
  bool operator==(const GroupErase&) const = default;
};
struct GroupSpeed {
  std::uint8_t group = 0;  // 255 = all
  std::uint16_t percent = 100;
  bool operator==(const GroupSpeed&) const = default;
};
struct GetBatteryVoltage {
  bool operator==(const GetBatteryVoltage&) const = default;
};
struct MultiServoOff {
  std::vector<std::uint8_t> servos;
  bool operator==(const MultiServoOff&) const = default;
};
struct ServoPositionRead {
  std::vector<std::uint8_t> servos;
  bool operator==(const ServoPositionRead&) const = default;
};
struct ServoOffsetWrite {
  std::vector<std::uint8_t> servos;
  bool operator==(const ServoOffsetWrite&) const = default;
};
struct ServoOffsetRead {
  std::vector<std::uint8_t> servos;
  bool operator==(const ServoOffsetRead&) const = default;
};
struct ServoOffsetAdjust {
  std::uint8_t servo = 0;
  std::int16_t offset = 0;  // -125..125
  bool operator==(const ServoOffsetAdjust&) const = default;
};
struct ServoSpeed {
  std::uint8_t servo = 0;
  ServoMode mode = ServoMode::servo;
  std::uint16_t milliseconds = 0;  // the spec's u16 (no range); the SDK sends -1000..1000 as i16
  bool operator==(const ServoSpeed&) const = default;
};
// The limits and LED settings of a bus servo: what BusServoInfoWrite sends, and what a
// board keeps (and persists) per servo.
struct BusServoLimits {
  std::uint8_t servo = 0;  // BusServoInfoWrite: sets the ID of the single servo on the bus
  std::uint16_t position_min = 0;
  std::uint16_t position_max = 1000;
  std::uint16_t millivolts_min = 4500;
  std::uint16_t millivolts_max = 12000;
  std::uint16_t temp_max = 85;
  std::uint8_t led_status = 0;   // 0 enable, 1 disable
  std::uint8_t led_warning = 0;  // bit0 overheat, bit1 overvoltage, bit2 overposition
  bool operator==(const BusServoLimits&) const = default;
};
using BusServoInfoWrite = BusServoLimits;
struct BusServoInfoRead {
  bool operator==(const BusServoInfoRead&) const = default;
};

using Request =
    std::variant<MultiServoMove, GroupDownloadBegin, GroupDownloadServoCount,
                 GroupDownloadBlocks, GroupDownloadAction, GroupDownloadEnd, GroupRun, GroupStop,
                 GroupErase, GroupSpeed, GetBatteryVoltage, MultiServoOff, ServoPositionRead,
                 ServoOffsetWrite, ServoOffsetRead, ServoOffsetAdjust, ServoSpeed,
                 BusServoInfoWrite, BusServoInfoRead>;

// ---------------------------------------------------------------- replies (board -> host)
struct GroupDownloadAck {
  std::uint8_t sub = 0;  // 1..5
  bool operator==(const GroupDownloadAck&) const = default;
};
struct GroupEraseReply {  // CMD 8 with no DATA
  bool operator==(const GroupEraseReply&) const = default;
};
struct BatteryVoltageReply {
  std::uint16_t millivolts = 0;
  bool operator==(const BatteryVoltageReply&) const = default;
};
struct ServoPosition {
  std::uint8_t servo = 0;
  std::int16_t position = 0;  // signed: can be slightly outside 0..1000 after offsets
  bool operator==(const ServoPosition&) const = default;
};
struct ServoPositionReply {
  std::vector<ServoPosition> positions;
  bool operator==(const ServoPositionReply&) const = default;
};
struct ServoOffset {
  std::uint8_t servo = 0;
  std::int8_t offset = 0;
  bool operator==(const ServoOffset&) const = default;
};
struct ServoOffsetReply {
  std::vector<ServoOffset> offsets;
  bool operator==(const ServoOffsetReply&) const = default;
};
struct BusServoInfoReply {
  std::uint8_t id = 0;
  std::uint16_t position_min = 0;
  std::uint16_t position_max = 0;
  std::uint16_t millivolts_min = 0;
  std::uint16_t millivolts_max = 0;
  std::uint16_t temp_max = 0;
  std::uint8_t led_status = 0;
  std::uint8_t led_warning = 0;
  std::int8_t offset = 0;
  std::int16_t position = 0;
  std::uint8_t temp = 0;
  std::uint16_t millivolts = 0;
  bool operator==(const BusServoInfoReply&) const = default;
};

// The reply for a servo with these limits and live readings.
BusServoInfoReply bus_servo_info_reply(const BusServoLimits& limits, std::int8_t offset,
                                       std::int16_t position, std::uint8_t temp,
                                       std::uint16_t millivolts);

// ---------------------------------------------------------------- notifications
enum class GroupEventKind : std::uint8_t { started, stopped, finished };
const char* to_string(GroupEventKind kind);  // "started", "stopped", "finished"

// started: CMD 6 `group count` (or no DATA on some boards); stopped: CMD 7 no DATA (some
// boards also send this when a group finishes: see the SDK); finished: CMD 8 `group count`.
struct GroupNotification {
  GroupEventKind kind = GroupEventKind::started;
  std::optional<std::uint8_t> group;   // absent in the no-DATA variants
  std::optional<std::uint16_t> count;  // absent in the no-DATA variants
  bool operator==(const GroupNotification&) const = default;
};

using BoardMessage = std::variant<GroupDownloadAck, GroupEraseReply, BatteryVoltageReply,
                                  ServoPositionReply, ServoOffsetReply, BusServoInfoReply,
                                  GroupNotification>;

// ---------------------------------------------------------------- encoders
// Requests that name servos are checked against `servos`; others ignore it.
Result<Frame> encode(const Request& request, const ServoRange& servos);
Result<Frame> encode(const BoardMessage& message);

// Splits an action count into the sub-1 run of bytes (300 -> FF 2D).
std::vector<std::uint8_t> action_count_bytes(std::uint16_t count);
// Blocks needed for `actions` actions (1..255 -> 1, 256..510 -> 2, ...).
std::uint8_t blocks_for_actions(int actions);

// ---------------------------------------------------------------- decoders
// A frame sent by a host, as a board reads it.
Result<Request> decode_request(const Frame& frame, const ServoRange& servos);
// A frame sent by a board, as a host reads it. CMD 8 with no DATA is the GroupErase reply;
// CMD 6/7/8 otherwise are notifications.
Result<BoardMessage> decode_board_message(const Frame& frame);

// The CMD of a message.
Command command_of(const Request& request);
std::uint8_t cmd_byte_of(const BoardMessage& message);

}  // namespace armctl::rc

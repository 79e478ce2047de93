// Encoders: check every value first (message_checks), then write the DATA bytes.
#include <initializer_list>
#include <type_traits>

#include "protocol/robot_commands/message_checks.hpp"
#include "protocol/robot_commands/messages.hpp"
#include "protocol/robot_commands/wire_bytes.hpp"

namespace armctl::rc {

BusServoInfoReply bus_servo_info_reply(const BusServoLimits& l, std::int8_t offset,
                                       std::int16_t position, std::uint8_t temp,
                                       std::uint16_t millivolts) {
  return BusServoInfoReply{l.servo,     l.position_min, l.position_max, l.millivolts_min,
                           l.millivolts_max, l.temp_max, l.led_status,   l.led_warning,
                           offset,      position,       temp,           millivolts};
}

const char* to_string(GroupEventKind kind) {
  switch (kind) {
    case GroupEventKind::started: return "started";
    case GroupEventKind::stopped: return "stopped";
    case GroupEventKind::finished: return "finished";
  }
  return "unknown";
}
namespace {

using wire::put_u16;
using wire::put_u8;

constexpr std::uint8_t code(Command c) { return static_cast<std::uint8_t>(c); }

// Reserving a whole report up front also keeps GCC 12's -Warray-bounds (a false positive
// on small vectors that grow after list-initialisation at -O3) quiet.
Frame start(std::uint8_t cmd, std::initializer_list<std::uint8_t> head) {
  Frame f;
  f.cmd = cmd;
  f.data.reserve(kMaxData);
  f.data.insert(f.data.end(), head.begin(), head.end());
  return f;
}

void put_targets(std::vector<std::uint8_t>& d, const std::vector<ServoTarget>& targets) {
  for (const auto& t : targets) {
    put_u8(d, t.servo);
    put_u16(d, t.position ? *t.position : kLeaveAlone);
  }
}

Frame servo_list_frame(Command c, const std::vector<std::uint8_t>& servos) {
  Frame f = start(code(c), {});
  put_u8(f.data, static_cast<std::uint8_t>(servos.size()));
  f.data.insert(f.data.end(), servos.begin(), servos.end());
  return f;
}

Result<Frame> refuse(const std::string& why) { return Error{ErrorKind::invalid_argument, why}; }

struct RequestEncoder {
  const ServoRange& servos;

  Result<Frame> operator()(const MultiServoMove& m) const {
    if (auto p = checks::check(m, servos)) return refuse(*p);
    Frame f = start(code(Command::MultiServoMove), {});
    put_u8(f.data, static_cast<std::uint8_t>(m.targets.size()));
    put_u16(f.data, m.time_ms);
    put_targets(f.data, m.targets);
    return f;
  }
  Result<Frame> operator()(const GroupDownloadBegin& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    Frame f = start(code(Command::GroupDownload), {1, m.group});
    for (auto b : action_count_bytes(m.action_count)) put_u8(f.data, b);
    return f;
  }
  Result<Frame> operator()(const GroupDownloadServoCount& m) const {
    if (auto p = checks::check(m, servos)) return refuse(*p);
    return Frame{code(Command::GroupDownload), {2, m.group, 0, m.servo_count, 0}};
  }
  Result<Frame> operator()(const GroupDownloadBlocks& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    Frame f = start(code(Command::GroupDownload), {3, m.group, 0});
    for (std::uint8_t b = 0; b < m.block_count; ++b) put_u8(f.data, b);
    return f;
  }
  Result<Frame> operator()(const GroupDownloadAction& m) const {
    if (auto p = checks::check(m, servos)) return refuse(*p);
    Frame f = start(code(Command::GroupDownload), {4, m.group, m.block, m.index});
    put_u8(f.data, static_cast<std::uint8_t>(2 + 3 * m.targets.size()));
    put_u16(f.data, m.time_ms);
    put_targets(f.data, m.targets);
    return f;
  }
  Result<Frame> operator()(const GroupDownloadEnd& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    return Frame{code(Command::GroupDownload), {5, m.group}};
  }
  Result<Frame> operator()(const GroupRun& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    Frame f = start(code(Command::GroupRun), {m.group});
    put_u16(f.data, m.count);
    return f;
  }
  Result<Frame> operator()(const GroupStop&) const { return Frame{code(Command::GroupStop), {}}; }
  Result<Frame> operator()(const GroupErase& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    return Frame{code(Command::GroupErase), {m.group}};
  }
  Result<Frame> operator()(const GroupSpeed& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    Frame f = start(code(Command::GroupSpeed), {m.group});
    put_u16(f.data, m.percent);
    return f;
  }
  Result<Frame> operator()(const GetBatteryVoltage&) const {
    return Frame{code(Command::GetBatteryVoltage), {}};
  }
  Result<Frame> operator()(const MultiServoOff& m) const {
    if (auto p = checks::check_servo_list("MultiServoOff", m.servos, servos)) return refuse(*p);
    return servo_list_frame(Command::MultiServoOff, m.servos);
  }
  Result<Frame> operator()(const ServoPositionRead& m) const {
    if (auto p = checks::check_servo_list("ServoPositionRead", m.servos, servos)) {
      return refuse(*p);
    }
    return servo_list_frame(Command::ServoPositionRead, m.servos);
  }
  Result<Frame> operator()(const ServoOffsetWrite& m) const {
    if (auto p = checks::check_servo_list("ServoOffsetWrite", m.servos, servos)) {
      return refuse(*p);
    }
    return servo_list_frame(Command::ServoOffsetWrite, m.servos);
  }
  Result<Frame> operator()(const ServoOffsetRead& m) const {
    if (auto p = checks::check_servo_list("ServoOffsetRead", m.servos, servos)) {
      return refuse(*p);
    }
    return servo_list_frame(Command::ServoOffsetRead, m.servos);
  }
  Result<Frame> operator()(const ServoOffsetAdjust& m) const {
    if (auto p = checks::check(m, servos)) return refuse(*p);
    Frame f = start(code(Command::ServoOffsetAdjust), {m.servo});
    put_u16(f.data, static_cast<std::uint16_t>(m.offset));
    return f;
  }
  Result<Frame> operator()(const ServoSpeed& m) const {
    if (auto p = checks::check(m, servos)) return refuse(*p);
    Frame f = start(code(Command::ServoSpeed), {m.servo, static_cast<std::uint8_t>(m.mode)});
    put_u16(f.data, m.milliseconds);
    return f;
  }
  Result<Frame> operator()(const BusServoInfoWrite& m) const {
    if (auto p = checks::check(m, servos)) return refuse(*p);
    Frame f = start(code(Command::BusServoInfoWrite), {m.servo});
    put_u16(f.data, m.position_min);
    put_u16(f.data, m.position_max);
    put_u16(f.data, m.millivolts_min);
    put_u16(f.data, m.millivolts_max);
    put_u16(f.data, m.temp_max);
    put_u8(f.data, m.led_status);
    put_u8(f.data, m.led_warning);
    return f;
  }
  Result<Frame> operator()(const BusServoInfoRead&) const {
    return Frame{code(Command::BusServoInfoRead), {}};
  }
};

struct BoardEncoder {
  Result<Frame> operator()(const GroupDownloadAck& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    return Frame{code(Command::GroupDownload), {m.sub, 0}};
  }
  Result<Frame> operator()(const GroupEraseReply&) const {
    return Frame{code(Command::GroupErase), {}};
  }
  Result<Frame> operator()(const BatteryVoltageReply& m) const {
    Frame f = start(code(Command::GetBatteryVoltage), {});
    put_u16(f.data, m.millivolts);
    return f;
  }
  Result<Frame> operator()(const ServoPositionReply& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    Frame f = start(code(Command::ServoPositionRead), {});
    put_u8(f.data, static_cast<std::uint8_t>(m.positions.size()));
    for (const auto& p : m.positions) {
      put_u8(f.data, p.servo);
      put_u16(f.data, static_cast<std::uint16_t>(p.position));
    }
    return f;
  }
  Result<Frame> operator()(const ServoOffsetReply& m) const {
    if (auto p = checks::check(m)) return refuse(*p);
    Frame f = start(code(Command::ServoOffsetRead), {});
    put_u8(f.data, static_cast<std::uint8_t>(m.offsets.size()));
    for (const auto& o : m.offsets) {
      put_u8(f.data, o.servo);
      put_u8(f.data, static_cast<std::uint8_t>(o.offset));
    }
    return f;
  }
  Result<Frame> operator()(const BusServoInfoReply& m) const {
    Frame f = start(code(Command::BusServoInfoRead), {m.id});
    put_u16(f.data, m.position_min);
    put_u16(f.data, m.position_max);
    put_u16(f.data, m.millivolts_min);
    put_u16(f.data, m.millivolts_max);
    put_u16(f.data, m.temp_max);
    put_u8(f.data, m.led_status);
    put_u8(f.data, m.led_warning);
    put_u8(f.data, static_cast<std::uint8_t>(m.offset));
    put_u16(f.data, static_cast<std::uint16_t>(m.position));
    put_u8(f.data, m.temp);
    put_u16(f.data, m.millivolts);
    return f;
  }
  Result<Frame> operator()(const GroupNotification& m) const {
    if (m.group.has_value() != m.count.has_value()) {
      return refuse("group notification: give both group and count, or neither");
    }
    switch (m.kind) {
      case GroupEventKind::started: {
        Frame f = start(kNotifyGroupStarted, {});
        if (m.group) {
          put_u8(f.data, *m.group);
          put_u16(f.data, *m.count);
        }
        return f;
      }
      case GroupEventKind::stopped:
        if (m.group) return refuse("group stopped notification carries no group or count");
        return Frame{kNotifyGroupStopped, {}};
      case GroupEventKind::finished: {
        // Without DATA, CMD 8 would read as the GroupErase reply: the finished variant
        // without DATA is CMD 7 (spec "Action groups").
        if (!m.group) return Frame{kNotifyGroupStopped, {}};
        Frame f = start(kNotifyGroupFinished, {*m.group});
        put_u16(f.data, *m.count);
        return f;
      }
    }
    return refuse("group notification: unknown kind");
  }
};

}  // namespace

std::vector<std::uint8_t> action_count_bytes(std::uint16_t count) {
  std::vector<std::uint8_t> out;
  int left = count;
  while (left > 255) {
    out.push_back(255);
    left -= 255;
  }
  if (left > 0 || out.empty()) out.push_back(static_cast<std::uint8_t>(left));
  return out;
}

std::uint8_t blocks_for_actions(int actions) {
  if (actions <= 0) return 0;
  return static_cast<std::uint8_t>((actions + kActionsPerBlock - 1) / kActionsPerBlock);
}

Result<Frame> encode(const Request& request, const ServoRange& servos) {
  return std::visit(RequestEncoder{servos}, request);
}

Result<Frame> encode(const BoardMessage& message) { return std::visit(BoardEncoder{}, message); }

Command command_of(const Request& request) {
  return std::visit(
      [](const auto& m) -> Command {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, MultiServoMove>) return Command::MultiServoMove;
        else if constexpr (std::is_same_v<T, GroupDownloadBegin> ||
                           std::is_same_v<T, GroupDownloadServoCount> ||
                           std::is_same_v<T, GroupDownloadBlocks> ||
                           std::is_same_v<T, GroupDownloadAction> ||
                           std::is_same_v<T, GroupDownloadEnd>)
          return Command::GroupDownload;
        else if constexpr (std::is_same_v<T, GroupRun>) return Command::GroupRun;
        else if constexpr (std::is_same_v<T, GroupStop>) return Command::GroupStop;
        else if constexpr (std::is_same_v<T, GroupErase>) return Command::GroupErase;
        else if constexpr (std::is_same_v<T, GroupSpeed>) return Command::GroupSpeed;
        else if constexpr (std::is_same_v<T, GetBatteryVoltage>) return Command::GetBatteryVoltage;
        else if constexpr (std::is_same_v<T, MultiServoOff>) return Command::MultiServoOff;
        else if constexpr (std::is_same_v<T, ServoPositionRead>) return Command::ServoPositionRead;
        else if constexpr (std::is_same_v<T, ServoOffsetWrite>) return Command::ServoOffsetWrite;
        else if constexpr (std::is_same_v<T, ServoOffsetRead>) return Command::ServoOffsetRead;
        else if constexpr (std::is_same_v<T, ServoOffsetAdjust>) return Command::ServoOffsetAdjust;
        else if constexpr (std::is_same_v<T, ServoSpeed>) return Command::ServoSpeed;
        else if constexpr (std::is_same_v<T, BusServoInfoWrite>) return Command::BusServoInfoWrite;
        else return Command::BusServoInfoRead;
      },
      request);
}

std::uint8_t cmd_byte_of(const BoardMessage& message) {
  return std::visit(
      [](const auto& m) -> std::uint8_t {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, GroupDownloadAck>) return code(Command::GroupDownload);
        else if constexpr (std::is_same_v<T, GroupEraseReply>) return code(Command::GroupErase);
        else if constexpr (std::is_same_v<T, BatteryVoltageReply>)
          return code(Command::GetBatteryVoltage);
        else if constexpr (std::is_same_v<T, ServoPositionReply>)
          return code(Command::ServoPositionRead);
        else if constexpr (std::is_same_v<T, ServoOffsetReply>)
          return code(Command::ServoOffsetRead);
        else if constexpr (std::is_same_v<T, BusServoInfoReply>)
          return code(Command::BusServoInfoRead);
        else {
          switch (m.kind) {
            case GroupEventKind::started: return kNotifyGroupStarted;
            case GroupEventKind::stopped: return kNotifyGroupStopped;
            case GroupEventKind::finished:
              return m.group ? kNotifyGroupFinished : kNotifyGroupStopped;
          }
          return kNotifyGroupStopped;
        }
      },
      message);
}

}  // namespace armctl::rc

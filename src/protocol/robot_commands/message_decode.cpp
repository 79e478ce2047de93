// Decoders: check the DATA length against the command's layout and counts, read the fields,
// then check every value (message_checks). Any problem gives an error and no message.
#include <fmt/core.h>

#include "protocol/robot_commands/message_checks.hpp"
#include "protocol/robot_commands/messages.hpp"
#include "protocol/robot_commands/wire_bytes.hpp"

namespace armctl::rc {
namespace {

Error bad(const std::string& why) { return Error{ErrorKind::protocol, why}; }

Error bad_length(const char* what, std::size_t got, const std::string& expected) {
  return bad(fmt::format("{}: DATA is {} bytes, expected {}", what, got, expected));
}

std::optional<Error> exact(const char* what, const Frame& f, std::size_t n) {
  if (f.data.size() != n) return bad_length(what, f.data.size(), std::to_string(n));
  return std::nullopt;
}

// A count byte followed by `entry` bytes per entry.
std::optional<Error> counted(const char* what, const Frame& f, std::size_t entry) {
  if (f.data.empty()) return bad_length(what, 0, "a count byte first");
  const std::size_t count = f.data[0];
  if (f.data.size() != 1 + entry * count) {
    return bad(fmt::format("{}: count {} needs {} bytes of DATA but the frame has {}", what,
                           count, 1 + entry * count, f.data.size()));
  }
  return std::nullopt;
}

template <typename T>
Result<Request> ok_request(T m, checks::Problem problem) {
  if (problem) return bad(*problem);
  return Request{std::move(m)};
}

std::vector<ServoTarget> read_targets(wire::Reader& r, std::size_t n) {
  std::vector<ServoTarget> out;
  for (std::size_t i = 0; i < n; ++i) {
    ServoTarget t;
    t.servo = r.u8();
    const std::uint16_t p = r.u16();
    if (p != kLeaveAlone) t.position = p;
    out.push_back(t);
  }
  return out;
}

Result<Request> decode_servo_list(const Frame& f, const char* what, const ServoRange& servos,
                                  auto make) {
  if (auto e = counted(what, f, 1)) return *e;
  std::vector<std::uint8_t> list(f.data.begin() + 1, f.data.end());
  auto problem = checks::check_servo_list(what, list, servos);
  return ok_request(make(std::move(list)), problem);
}

Result<Request> decode_group_download(const Frame& f, const ServoRange& servos) {
  const auto& d = f.data;
  if (d.size() < 2) return bad_length("GroupDownload", d.size(), "at least 2 (sub, group)");
  const std::uint8_t sub = d[0];
  const std::uint8_t group = d[1];
  switch (sub) {
    case 1: {
      if (d.size() < 3 || d.size() > 2 + 5) {
        return bad_length("GroupDownload begin", d.size(),
                          "3..7 (sub, group, 1..5 count bytes)");
      }
      int sum = 0;
      for (std::size_t i = 2; i < d.size(); ++i) sum += d[i];
      GroupDownloadBegin m{group, static_cast<std::uint16_t>(sum)};
      if (sum > kActionsMax) {
        return bad(fmt::format("GroupDownload begin: action count {} is out of range (allowed "
                               "1..{})",
                               sum, kActionsMax));
      }
      return ok_request(m, checks::check(m));
    }
    case 2: {
      if (auto e = exact("GroupDownload servo count", f, 5)) return *e;
      if (d[2] != 0 || d[4] != 0) {
        return bad("GroupDownload servo count: expected `group 00 count 00`, got " + to_hex(d));
      }
      GroupDownloadServoCount m{group, d[3]};
      return ok_request(m, checks::check(m, servos));
    }
    case 3: {
      if (d.size() < 4 || d.size() > 3 + kBlocksMax) {
        return bad_length("GroupDownload blocks", d.size(), "4..7 (sub, group, 00, blocks)");
      }
      if (d[2] != 0) return bad("GroupDownload blocks: third byte must be 00, got " + to_hex(d));
      for (std::size_t i = 3; i < d.size(); ++i) {
        if (d[i] != i - 3) {
          return bad(fmt::format("GroupDownload blocks: block list must be 00, 01, .. in order; "
                                 "byte {} is {}",
                                 i, d[i]));
        }
      }
      GroupDownloadBlocks m{group, static_cast<std::uint8_t>(d.size() - 3)};
      return ok_request(m, checks::check(m));
    }
    case 4: {
      if (d.size() < 7) {
        return bad_length("GroupDownload action", d.size(),
                          "at least 7 (sub group block index bytes ms)");
      }
      const std::size_t following = d[4];
      if (following != d.size() - 5) {
        return bad(fmt::format("GroupDownload action: byte count {} disagrees with the {} bytes "
                               "that follow it",
                               following, d.size() - 5));
      }
      if ((following - 2) % 3 != 0) {
        return bad(fmt::format("GroupDownload action: byte count {} is not 2 + 3 n", following));
      }
      wire::Reader r(d);
      GroupDownloadAction m;
      r.u8();
      m.group = r.u8();
      m.block = r.u8();
      m.index = r.u8();
      r.u8();
      m.time_ms = r.u16();
      m.targets = read_targets(r, (following - 2) / 3);
      return ok_request(m, checks::check(m, servos));
    }
    case 5: {
      if (auto e = exact("GroupDownload end", f, 2)) return *e;
      GroupDownloadEnd m{group};
      return ok_request(m, checks::check(m));
    }
    default:
      return bad(fmt::format("GroupDownload: sub-command {} is not allowed (1..5)", sub));
  }
}

}  // namespace

Result<Request> decode_request(const Frame& f, const ServoRange& servos) {
  const auto cmd = command_from_byte(f.cmd);
  if (!cmd) {
    return bad(fmt::format("unknown CMD 0x{:02X} (allowed: 3, 5, 6, 7, 8, 11, 15, 20..24, 26..28)",
                           f.cmd));
  }
  const auto& d = f.data;
  wire::Reader r(d);
  switch (*cmd) {
    case Command::MultiServoMove: {
      if (d.size() < 3) return bad_length("MultiServoMove", d.size(), "at least 3");
      const std::size_t count = d[0];
      if (d.size() != 3 + 3 * count) {
        return bad(fmt::format("MultiServoMove: count {} needs {} bytes of DATA but the frame has "
                               "{}",
                               count, 3 + 3 * count, d.size()));
      }
      MultiServoMove m;
      r.u8();
      m.time_ms = r.u16();
      m.targets = read_targets(r, count);
      return ok_request(m, checks::check(m, servos));
    }
    case Command::GroupDownload: return decode_group_download(f, servos);
    case Command::GroupRun: {
      if (auto e = exact("GroupRun", f, 3)) return *e;
      GroupRun m{r.u8(), 0};
      m.count = r.u16();
      return ok_request(m, checks::check(m));
    }
    case Command::GroupStop:
      if (auto e = exact("GroupStop", f, 0)) return *e;
      return Request{GroupStop{}};
    case Command::GroupErase: {
      if (auto e = exact("GroupErase", f, 1)) return *e;
      GroupErase m{d[0]};
      return ok_request(m, checks::check(m));
    }
    case Command::GroupSpeed: {
      if (auto e = exact("GroupSpeed", f, 3)) return *e;
      GroupSpeed m{r.u8(), 0};
      m.percent = r.u16();
      return ok_request(m, checks::check(m));
    }
    case Command::GetBatteryVoltage:
      if (auto e = exact("GetBatteryVoltage", f, 0)) return *e;
      return Request{GetBatteryVoltage{}};
    case Command::MultiServoOff:
      return decode_servo_list(f, "MultiServoOff", servos,
                               [](auto l) { return MultiServoOff{std::move(l)}; });
    case Command::ServoPositionRead:
      return decode_servo_list(f, "ServoPositionRead", servos,
                               [](auto l) { return ServoPositionRead{std::move(l)}; });
    case Command::ServoOffsetWrite:
      return decode_servo_list(f, "ServoOffsetWrite", servos,
                               [](auto l) { return ServoOffsetWrite{std::move(l)}; });
    case Command::ServoOffsetRead:
      return decode_servo_list(f, "ServoOffsetRead", servos,
                               [](auto l) { return ServoOffsetRead{std::move(l)}; });
    case Command::ServoOffsetAdjust: {
      if (auto e = exact("ServoOffsetAdjust", f, 3)) return *e;
      ServoOffsetAdjust m{r.u8(), 0};
      m.offset = r.s16();
      return ok_request(m, checks::check(m, servos));
    }
    case Command::ServoSpeed: {
      if (auto e = exact("ServoSpeed", f, 4)) return *e;
      ServoSpeed m;
      m.servo = r.u8();
      m.mode = static_cast<ServoMode>(r.u8());
      m.milliseconds = r.u16();
      return ok_request(m, checks::check(m, servos));
    }
    case Command::BusServoInfoWrite: {
      if (auto e = exact("BusServoInfoWrite", f, 13)) return *e;
      BusServoInfoWrite m;
      m.servo = r.u8();
      m.position_min = r.u16();
      m.position_max = r.u16();
      m.millivolts_min = r.u16();
      m.millivolts_max = r.u16();
      m.temp_max = r.u16();
      m.led_status = r.u8();
      m.led_warning = r.u8();
      return ok_request(m, checks::check(m, servos));
    }
    case Command::BusServoInfoRead:
      if (auto e = exact("BusServoInfoRead", f, 0)) return *e;
      return Request{BusServoInfoRead{}};
  }
  return bad("unknown command");
}

Result<BoardMessage> decode_board_message(const Frame& f) {
  const auto& d = f.data;
  wire::Reader r(d);
  switch (f.cmd) {
    case static_cast<std::uint8_t>(Command::GroupDownload): {
      if (auto e = exact("GroupDownload reply", f, 2)) return *e;
      if (d[1] != 0) return bad("GroupDownload reply: second byte must be 00, got " + to_hex(d));
      GroupDownloadAck m{d[0]};
      if (auto p = checks::check(m)) return bad(*p);
      return BoardMessage{m};
    }
    case kNotifyGroupStarted:
      if (d.empty()) return BoardMessage{GroupNotification{GroupEventKind::started, {}, {}}};
      if (d.size() != 3) return bad_length("group started notification", d.size(), "0 or 3");
      {
        GroupNotification n{GroupEventKind::started, r.u8(), {}};
        n.count = r.u16();
        return BoardMessage{n};
      }
    case kNotifyGroupStopped:
      if (auto e = exact("group stopped notification", f, 0)) return *e;
      return BoardMessage{GroupNotification{GroupEventKind::stopped, {}, {}}};
    case kNotifyGroupFinished:
      if (d.empty()) return BoardMessage{GroupEraseReply{}};
      if (d.size() != 3) {
        return bad_length("group finished notification", d.size(), "3 (0 = GroupErase reply)");
      }
      {
        GroupNotification n{GroupEventKind::finished, r.u8(), {}};
        n.count = r.u16();
        return BoardMessage{n};
      }
    case static_cast<std::uint8_t>(Command::GetBatteryVoltage):
      if (auto e = exact("GetBatteryVoltage reply", f, 2)) return *e;
      return BoardMessage{BatteryVoltageReply{r.u16()}};
    case static_cast<std::uint8_t>(Command::ServoPositionRead): {
      if (auto e = counted("ServoPositionRead reply", f, 3)) return *e;
      ServoPositionReply m;
      const std::size_t n = r.u8();
      for (std::size_t i = 0; i < n; ++i) {
        ServoPosition p;
        p.servo = r.u8();
        p.position = r.s16();
        m.positions.push_back(p);
      }
      if (auto p = checks::check(m)) return bad(*p);
      return BoardMessage{m};
    }
    case static_cast<std::uint8_t>(Command::ServoOffsetRead): {
      if (auto e = counted("ServoOffsetRead reply", f, 2)) return *e;
      ServoOffsetReply m;
      const std::size_t n = r.u8();
      for (std::size_t i = 0; i < n; ++i) {
        ServoOffset o;
        o.servo = r.u8();
        o.offset = r.s8();
        m.offsets.push_back(o);
      }
      if (auto p = checks::check(m)) return bad(*p);
      return BoardMessage{m};
    }
    case static_cast<std::uint8_t>(Command::BusServoInfoRead): {
      if (auto e = exact("BusServoInfoRead reply", f, 19)) return *e;
      BusServoInfoReply m;
      m.id = r.u8();
      m.position_min = r.u16();
      m.position_max = r.u16();
      m.millivolts_min = r.u16();
      m.millivolts_max = r.u16();
      m.temp_max = r.u16();
      m.led_status = r.u8();
      m.led_warning = r.u8();
      m.offset = r.s8();
      m.position = r.s16();
      m.temp = r.u8();
      m.millivolts = r.u16();
      return BoardMessage{m};
    }
    default:
      return bad(fmt::format("CMD 0x{:02X} is not a reply or notification a board sends "
                             "(allowed: 5, 6, 7, 8, 15, 21, 23, 28)",
                             f.cmd));
  }
}

}  // namespace armctl::rc

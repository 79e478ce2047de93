#include "protocol/robot_commands/message_checks.hpp"

#include <algorithm>
#include <set>

#include <fmt/core.h>

namespace armctl::rc::checks {
namespace {

std::string range_text(const ServoRange& servos) {
  return fmt::format("{}..{}", servos.first, servos.last);
}

Problem check_servo(const char* command, const char* field, int servo, const ServoRange& servos) {
  if (!servos.contains(servo)) {
    return fmt::format("{}: {} {} is not present on this board (allowed {})", command, field,
                       servo, range_text(servos));
  }
  return std::nullopt;
}

Problem check_group(const char* command, int group, bool all_allowed) {
  if (group <= kGroupMax) return std::nullopt;
  if (all_allowed && group == kAllGroups) return std::nullopt;
  return fmt::format("{}: group {} is out of range (allowed 0..{}{})", command, group, kGroupMax,
                     all_allowed ? " or 255 = all" : "");
}

Problem check_targets(const char* command, std::uint16_t time_ms,
                      const std::vector<ServoTarget>& targets, const ServoRange& servos,
                      bool allow_null) {
  if (time_ms > kMoveTimeMaxMs) {
    return fmt::format("{}: time {} ms is out of range (allowed 0..{} ms)", command, time_ms,
                       kMoveTimeMaxMs);
  }
  if (targets.empty() || targets.size() > kMaxServosPerFrame ||
      static_cast<int>(targets.size()) > servos.count()) {
    return fmt::format("{}: {} servo entries given (allowed 1..{})", command, targets.size(),
                       std::min<int>(servos.count(), kMaxServosPerFrame));
  }
  std::set<int> seen;
  for (const auto& t : targets) {
    if (auto p = check_servo(command, "servo", t.servo, servos)) return p;
    if (!seen.insert(t.servo).second) {
      return fmt::format("{}: servo {} appears more than once (each servo at most once)",
                         command, t.servo);
    }
    if (!t.position) {
      if (!allow_null) {
        return fmt::format("{}: servo {} has no position (every entry needs 0..{})", command,
                           t.servo, kPositionMax);
      }
      continue;
    }
    if (*t.position > kPositionMax) {
      return fmt::format("{}: servo {} position {} is out of range (allowed {}..{}, or {} = leave "
                         "alone)",
                         command, t.servo, *t.position, kPositionMin, kPositionMax,
                         "0xFF00");
    }
  }
  return std::nullopt;
}

}  // namespace

Problem check(const MultiServoMove& m, const ServoRange& servos) {
  return check_targets("MultiServoMove", m.time_ms, m.targets, servos, true);
}

Problem check(const GroupDownloadBegin& m) {
  if (auto p = check_group("GroupDownload begin", m.group, false)) return p;
  if (m.action_count < 1 || m.action_count > kActionsMax) {
    return fmt::format("GroupDownload begin: action count {} is out of range (allowed 1..{})",
                       m.action_count, kActionsMax);
  }
  return std::nullopt;
}

Problem check(const GroupDownloadServoCount& m, const ServoRange& servos) {
  if (auto p = check_group("GroupDownload servo count", m.group, false)) return p;
  if (m.servo_count < 1 || m.servo_count > servos.count()) {
    return fmt::format("GroupDownload servo count: {} servos per action (allowed 1..{})",
                       m.servo_count, servos.count());
  }
  return std::nullopt;
}

Problem check(const GroupDownloadBlocks& m) {
  if (auto p = check_group("GroupDownload blocks", m.group, false)) return p;
  if (m.block_count < 1 || m.block_count > kBlocksMax) {
    return fmt::format("GroupDownload blocks: {} blocks (allowed 1..{})", m.block_count,
                       kBlocksMax);
  }
  return std::nullopt;
}

Problem check(const GroupDownloadAction& m, const ServoRange& servos) {
  if (auto p = check_group("GroupDownload action", m.group, false)) return p;
  if (m.block >= kBlocksMax) {
    return fmt::format("GroupDownload action: block {} is out of range (allowed 0..{})", m.block,
                       kBlocksMax - 1);
  }
  if (m.index >= kActionsPerBlock) {
    return fmt::format("GroupDownload action: index {} is outside its block (allowed 0..{})",
                       m.index, kActionsPerBlock - 1);
  }
  return check_targets("GroupDownload action", m.time_ms, m.targets, servos, true);
}

Problem check(const GroupDownloadEnd& m) { return check_group("GroupDownload end", m.group, false); }
Problem check(const GroupRun& m) { return check_group("GroupRun", m.group, false); }
Problem check(const GroupErase& m) { return check_group("GroupErase", m.group, true); }

Problem check(const GroupSpeed& m) {
  if (auto p = check_group("GroupSpeed", m.group, true)) return p;
  if (m.percent < kSpeedPercentMin || m.percent > kSpeedPercentMax) {
    return fmt::format("GroupSpeed: percentage {} is out of range (allowed {}..{}, 100 = as "
                       "recorded)",
                       m.percent, kSpeedPercentMin, kSpeedPercentMax);
  }
  return std::nullopt;
}

Problem check_servo_list(const char* command, const std::vector<std::uint8_t>& list,
                         const ServoRange& servos) {
  if (list.empty() || static_cast<int>(list.size()) > servos.count()) {
    return fmt::format("{}: {} servos given (allowed 1..{})", command, list.size(),
                       servos.count());
  }
  std::set<int> seen;
  for (auto s : list) {
    if (auto p = check_servo(command, "servo", s, servos)) return p;
    if (!seen.insert(s).second) {
      return fmt::format("{}: servo {} appears more than once (each servo at most once)",
                         command, s);
    }
  }
  return std::nullopt;
}

Problem check(const ServoOffsetAdjust& m, const ServoRange& servos) {
  if (auto p = check_servo("ServoOffsetAdjust", "servo", m.servo, servos)) return p;
  if (m.offset < kOffsetMin || m.offset > kOffsetMax) {
    return fmt::format("ServoOffsetAdjust: offset {} is out of range (allowed {}..{})", m.offset,
                       kOffsetMin, kOffsetMax);
  }
  return std::nullopt;
}

Problem check(const ServoSpeed& m, const ServoRange& servos) {
  if (auto p = check_servo("ServoSpeed", "servo", m.servo, servos)) return p;
  if (m.mode != ServoMode::servo && m.mode != ServoMode::motor) {
    return fmt::format("ServoSpeed: mode {} is not allowed (0 = servo, 1 = motor)",
                       static_cast<int>(m.mode));
  }
  return std::nullopt;
}

Problem check(const BusServoInfoWrite& m, const ServoRange& servos) {
  const char* c = "BusServoInfoWrite";
  if (auto p = check_servo(c, "servo", m.servo, servos)) return p;
  if (m.position_max > kPositionMax || m.position_min > m.position_max) {
    return fmt::format("{}: position limits {}..{} are not allowed (need 0 <= min <= max <= {})",
                       c, m.position_min, m.position_max, kPositionMax);
  }
  if (m.millivolts_min < kMillivoltsMin || m.millivolts_max > kMillivoltsMax ||
      m.millivolts_min > m.millivolts_max) {
    return fmt::format("{}: voltage limits {}..{} mV are not allowed (need {} <= min <= max <= {})",
                       c, m.millivolts_min, m.millivolts_max, kMillivoltsMin, kMillivoltsMax);
  }
  if (m.temp_max < kTempMaxMin || m.temp_max > kTempMaxMax) {
    return fmt::format("{}: temperature limit {} C is out of range (allowed {}..{})", c,
                       m.temp_max, kTempMaxMin, kTempMaxMax);
  }
  if (m.led_status > 1) {
    return fmt::format("{}: led_status {} is not allowed (0 = enable, 1 = disable)", c,
                       m.led_status);
  }
  if (m.led_warning > 7) {
    return fmt::format("{}: led_warning {} is not allowed (bits 0..2 only: 0..7)", c,
                       m.led_warning);
  }
  return std::nullopt;
}

Problem check(const GroupDownloadAck& m) {
  if (m.sub < 1 || m.sub > 5) {
    return fmt::format("GroupDownload reply: sub {} is not a sub-command (allowed 1..5)", m.sub);
  }
  return std::nullopt;
}

Problem check(const ServoPositionReply& m) {
  if (m.positions.empty() || m.positions.size() > kMaxServosPerFrame) {
    return fmt::format("ServoPositionRead reply: {} entries (allowed 1..{})", m.positions.size(),
                       kMaxServosPerFrame);
  }
  return std::nullopt;
}

Problem check(const ServoOffsetReply& m) {
  if (m.offsets.empty() || m.offsets.size() > kMaxServosPerFrame) {
    return fmt::format("ServoOffsetRead reply: {} entries (allowed 1..{})", m.offsets.size(),
                       kMaxServosPerFrame);
  }
  for (const auto& o : m.offsets) {
    if (o.offset < kOffsetMin || o.offset > kOffsetMax) {
      return fmt::format("ServoOffsetRead reply: servo {} offset {} is out of range (allowed "
                         "{}..{})",
                         o.servo, o.offset, kOffsetMin, kOffsetMax);
    }
  }
  return std::nullopt;
}

}  // namespace armctl::rc::checks

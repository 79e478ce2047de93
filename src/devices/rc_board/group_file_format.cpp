#include "devices/rc_board/group_file_format.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/core.h>

#include "devices/rc_board/crc32.hpp"

namespace armctl::rc_board {
namespace {

constexpr char kMagic[8] = {'A', 'R', 'M', 'G', 'R', 'P', '1', '\n'};
constexpr std::size_t kHeader = 8 + 1 + 1 + 2;

void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

std::uint16_t get16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}

Error corrupt(std::string message) {
  return Error{ErrorKind::invalid_config, std::move(message)};
}

}  // namespace

std::vector<std::uint8_t> encode_group_file(GroupNumber group, const ActionGroup& g) {
  std::vector<std::uint8_t> out(kMagic, kMagic + sizeof kMagic);
  out.push_back(group);
  out.push_back(g.servo_count);
  put16(out, static_cast<std::uint16_t>(g.actions.size()));
  for (const Action& a : g.actions) {
    put16(out, a.milliseconds);
    for (const ServoTarget& t : a.positions) {
      out.push_back(t.servo);
      put16(out, t.position.value_or(rc::kLeaveAlone));  // stored as on the wire
    }
  }
  std::uint32_t crc = crc32(out);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(crc >> (8 * i)));
  return out;
}

Result<ActionGroup> decode_group_file(std::span<const std::uint8_t> b, GroupNumber expected) {
  if (b.size() < kHeader + 4 || std::memcmp(b.data(), kMagic, sizeof kMagic) != 0)
    return corrupt("not a group file (bad magic or too short)");
  std::uint32_t stored = 0;
  for (int i = 0; i < 4; ++i) stored |= std::uint32_t{b[b.size() - 4 + i]} << (8 * i);
  if (crc32(b.first(b.size() - 4)) != stored) return corrupt("CRC mismatch (torn or corrupted)");
  ActionGroup g;
  if (b[8] != expected)
    return corrupt(fmt::format("file holds group {} but is named for group {}", b[8], expected));
  g.servo_count = b[9];
  std::size_t count = get16(b, 10);
  if (g.servo_count == 0 || count == 0 || count > rc::kActionsMax)
    return corrupt(
        fmt::format("servo count {} / action count {} out of range", g.servo_count, count));
  std::size_t per_action = 2 + 3 * std::size_t{g.servo_count};
  if (b.size() != kHeader + count * per_action + 4) return corrupt("length disagrees with counts");
  std::size_t at = kHeader;
  g.actions.resize(count);
  for (Action& a : g.actions) {
    a.milliseconds = get16(b, at);
    at += 2;
    if (a.milliseconds > rc::kMoveTimeMaxMs) return corrupt("action time above 30000 ms");
    a.positions.resize(g.servo_count);
    for (ServoTarget& t : a.positions) {
      t.servo = b[at];
      const std::uint16_t position = get16(b, at + 1);
      at += 3;
      if (position == rc::kLeaveAlone) {
        t.position.reset();
      } else if (position > rc::kPositionMax) {
        return corrupt("position out of range");
      } else {
        t.position = position;
      }
    }
  }
  return g;
}

}  // namespace armctl::rc_board

#include "files/rob_file.hpp"

#include <algorithm>
#include <iterator>
#include <string>

#include <fmt/core.h>

#include "core/regular_file.hpp"

namespace armctl::files {

namespace {

constexpr std::string_view kMagic = "SOBARM";
constexpr std::size_t kCountOffset = 6;
constexpr std::uint16_t kMaxTimeMs = 30000;
constexpr std::uint16_t kMaxPosition = 1000;

std::uint16_t u16_at(const std::vector<std::uint8_t>& b, std::size_t offset) {
  return std::uint16_t(b[offset] | (b[offset + 1] << 8));
}

void put_u16(std::vector<std::uint8_t>& b, std::uint16_t v) {
  b.push_back(std::uint8_t(v & 0xFF));
  b.push_back(std::uint8_t(v >> 8));
}

// Bytes as people compare them with a hex dump: "53 4f 42".
std::string hex(const std::vector<std::uint8_t>& b, std::size_t offset, std::size_t n) {
  std::string out;
  for (std::size_t i = offset; i < offset + n && i < b.size(); ++i)
    out += fmt::format("{}{:02x}", out.empty() ? "" : " ", b[i]);
  return out;
}

Error bad(std::string_view source, std::size_t offset, const std::string& what) {
  return Error{ErrorKind::invalid_config, fmt::format("{}: offset {}: {}", source, offset, what)};
}

}  // namespace

Result<ActionGroupFile> parse_rob_file(const std::vector<std::uint8_t>& bytes, std::string_view source) {
  if (bytes.size() < kRobHeaderBytes)
    return bad(source, 0,
               fmt::format("{} bytes; a .rob file is a {}-byte header ('SOBARM', frame count) then "
                           "{}-byte frames",
                           bytes.size(), kRobHeaderBytes, kRobFrameBytes));
  if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin()))
    return bad(source, 0, fmt::format("found bytes {}; a .rob file starts with 'SOBARM' (53 4f 42 41 52 4d)",
                                      hex(bytes, 0, kMagic.size())));
  const std::size_t count = u16_at(bytes, kCountOffset);
  if (count < 1 || count > kRobMaxFrames)
    return bad(source, kCountOffset,
               fmt::format("frame count {} (bytes {}); allowed is 1..{}", count, hex(bytes, kCountOffset, 2),
                           kRobMaxFrames));
  const std::size_t expected = kRobHeaderBytes + count * kRobFrameBytes;
  if (bytes.size() != expected) {
    const std::size_t body = bytes.size() - kRobHeaderBytes;
    return bad(source, kCountOffset,
               fmt::format("frame count {} needs {} bytes ({} + {} x {}); the file has {} ({} frame{}{})", count,
                           expected, kRobHeaderBytes, count, kRobFrameBytes, bytes.size(), body / kRobFrameBytes,
                           body / kRobFrameBytes == 1 ? "" : "s",
                           body % kRobFrameBytes ? fmt::format(" and {} bytes", body % kRobFrameBytes) : ""));
  }
  ActionGroupFile group;
  for (std::size_t s = 1; s <= kRobServos; ++s) group.servos.push_back(std::uint8_t(s));
  for (std::size_t f = 0; f < count; ++f) {
    const std::size_t at = kRobHeaderBytes + f * kRobFrameBytes;
    rc::GroupAction action;
    action.time_ms = u16_at(bytes, at);
    if (action.time_ms > kMaxTimeMs)
      return bad(source, at, fmt::format("frame {}: time {} ms; allowed is 0..{}", f + 1, action.time_ms, kMaxTimeMs));
    for (std::size_t s = 0; s < kRobServos; ++s) {
      const std::size_t p_at = at + 2 + 2 * s;
      const std::uint16_t p = u16_at(bytes, p_at);
      if (p > kMaxPosition)
        return bad(source, p_at,
                   fmt::format("frame {}: servo {} position {} (bytes {}); allowed is 0..{}", f + 1, s + 1, p,
                               hex(bytes, p_at, 2), kMaxPosition));
      action.targets.push_back({std::uint8_t(s + 1), p});
    }
    group.actions.push_back(std::move(action));
  }
  return group;
}

Result<ActionGroupFile> read_rob_file(const std::filesystem::path& path) {
  auto text = read_regular_file(path, ".rob file", kRobMaxBytes);
  if (!text) return text.error();
  const std::vector<std::uint8_t> bytes(text->begin(), text->end());
  return parse_rob_file(bytes, path.string());
}

Result<std::vector<std::uint8_t>> format_rob_file(const ActionGroupFile& group) {
  auto refuse = [](const std::string& what) { return Error{ErrorKind::invalid_argument, what}; };
  std::vector<std::uint8_t> sorted = group.servos;
  std::sort(sorted.begin(), sorted.end());
  if (sorted != std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6}) {
    std::string ids;
    for (auto s : group.servos) ids += fmt::format("{}{}", ids.empty() ? "" : ",", s);
    return refuse(fmt::format("the group names servos {}; a .rob file holds exactly servos 1..6", ids));
  }
  if (group.actions.empty() || group.actions.size() > kRobMaxFrames)
    return refuse(fmt::format("the group has {} actions; a .rob file holds 1..{}", group.actions.size(), kRobMaxFrames));
  std::vector<std::uint8_t> out(kMagic.begin(), kMagic.end());
  put_u16(out, std::uint16_t(group.actions.size()));
  out.resize(kRobHeaderBytes, 0);
  for (std::size_t a = 0; a < group.actions.size(); ++a) {
    const auto& action = group.actions[a];
    if (action.time_ms > kMaxTimeMs)
      return refuse(fmt::format("action {}: time {} ms; a .rob frame allows 0..{}", a + 1, action.time_ms, kMaxTimeMs));
    put_u16(out, action.time_ms);
    for (std::uint8_t s = 1; s <= kRobServos; ++s) {
      auto t = std::find_if(action.targets.begin(), action.targets.end(), [s](const auto& x) { return x.servo == s; });
      if (t == action.targets.end() || !t->position)
        return refuse(fmt::format("action {}: servo {} is 'keep' or missing; a .rob frame gives every position", a + 1, s));
      if (*t->position > kMaxPosition)
        return refuse(fmt::format("action {}: servo {} position {}; allowed is 0..{}", a + 1, s, *t->position, kMaxPosition));
      put_u16(out, *t->position);
    }
  }
  return out;
}

}  // namespace armctl::files

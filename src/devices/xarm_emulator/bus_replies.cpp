#include "devices/xarm_emulator/bus_replies.hpp"

namespace armctl::xarm {

std::vector<std::uint8_t> servo_reply_frame(std::uint8_t id, std::uint8_t cmd, std::span<const std::uint8_t> params) {
  const auto len = static_cast<std::uint8_t>(3 + params.size());
  std::vector<std::uint8_t> frame{0x55, 0x55, id, len, cmd};
  unsigned sum = id + len + cmd;
  for (std::uint8_t p : params) {
    frame.push_back(p);
    sum += p;
  }
  frame.push_back(static_cast<std::uint8_t>(~sum & 0xFF));
  return frame;
}

std::optional<std::vector<std::uint8_t>> read_over_bus(std::uint8_t id, std::uint8_t cmd,
                                                       std::span<const std::vector<std::uint8_t>> answers) {
  if (answers.empty()) return std::nullopt;  // nobody answered: the board's read times out
  std::vector<std::uint8_t> line = servo_reply_frame(id, cmd, answers[0]);
  for (std::size_t i = 1; i < answers.size(); ++i) {
    const std::vector<std::uint8_t> frame = servo_reply_frame(id, cmd, answers[i]);
    for (std::size_t b = 0; b < line.size(); ++b) line[b] &= frame[b];  // dominant low
  }
  // Header, ID, LEN and CMD are the same in every frame, so they survive the AND; only the
  // checksum can give the collision away.
  unsigned sum = 0;
  for (std::size_t b = 2; b + 1 < line.size(); ++b) sum += line[b];
  if (line.back() != static_cast<std::uint8_t>(~sum & 0xFF)) return std::nullopt;
  return std::vector<std::uint8_t>(line.begin() + 5, line.end() - 1);
}

}  // namespace armctl::xarm

#include "devices/joint_bus/sim_link_protocol.hpp"

#include <fmt/core.h>

namespace armctl::joint_bus::sim_link {

namespace {
bool known_type(std::uint8_t t) {
  switch (static_cast<Type>(t)) {
    case Type::select:
    case Type::write:
    case Type::flush:
    case Type::hello:
    case Type::received:
    case Type::flushed:
    case Type::error: return true;
  }
  return false;
}
}  // namespace

std::vector<std::uint8_t> encode(Type type, std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out;
  out.reserve(payload.size() + 2);
  out.push_back(static_cast<std::uint8_t>(type));
  out.push_back(static_cast<std::uint8_t>(payload.size()));
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

void Parser::push(std::span<const std::uint8_t> bytes) {
  if (begin_ > 4096) {  // keep the buffer from growing without bound
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(begin_));
    begin_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

std::optional<Message> Parser::next() {
  if (error_) return std::nullopt;
  const std::size_t avail = buffer_.size() - begin_;
  if (avail < 2) return std::nullopt;
  const std::uint8_t type = buffer_[begin_];
  if (!known_type(type)) {
    error_ = fmt::format("unknown sim link message type 0x{:02X} (allowed: S W F H R f E)", type);
    return std::nullopt;
  }
  const std::size_t len = buffer_[begin_ + 1];
  if (avail < 2 + len) return std::nullopt;
  Message m{static_cast<Type>(type),
            std::vector<std::uint8_t>(buffer_.begin() + static_cast<std::ptrdiff_t>(begin_ + 2),
                                      buffer_.begin() + static_cast<std::ptrdiff_t>(begin_ + 2 + len))};
  begin_ += 2 + len;
  return m;
}

}  // namespace armctl::joint_bus::sim_link

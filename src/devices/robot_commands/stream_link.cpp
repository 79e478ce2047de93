#include "devices/robot_commands/stream_link.hpp"

#include <array>

namespace armctl::robot_commands {

StreamLink::StreamLink(std::unique_ptr<transport::ByteStream> stream, std::string description, std::uint32_t baud)
    : stream_(std::move(stream)), description_(std::move(description)), baud_(baud) {}

void StreamLink::send(const rc::Frame& frame) { stream_->write(rc::encode_frame(frame)); }

std::optional<rc::Frame> StreamLink::receive(TimePoint deadline) {
  for (;;) {
    if (auto f = receiver_.next()) return f;
    std::array<std::uint8_t, 256> buf{};
    const std::size_t n = stream_->read(buf, deadline);
    if (n == 0) {
      // Timed out. A partial frame stays buffered: its remaining bytes may still come.
      return std::nullopt;
    }
    // With the arrival time: a partial frame whose bytes stopped (a board reset mid-reply)
    // is dropped instead of joining the next reply.
    receiver_.feed(std::span<const std::uint8_t>(buf.data(), n), clock().now());
  }
}

}  // namespace armctl::robot_commands

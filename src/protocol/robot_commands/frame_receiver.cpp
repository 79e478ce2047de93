#include "protocol/robot_commands/frame_receiver.hpp"

#include <algorithm>

namespace armctl::rc {

Duration frame_gap(std::uint32_t baud) {
  return std::max<Duration>(wire_time(20, baud), std::chrono::milliseconds(50));
}

void FrameReceiver::feed(std::span<const std::uint8_t> bytes) {
  for (std::uint8_t b : bytes) feed_byte(b);
}

void FrameReceiver::feed(std::span<const std::uint8_t> bytes, TimePoint arrived) {
  if (bytes.empty()) return;
  if (mid_frame() && last_byte_ && arrived - *last_byte_ > gap_) {
    ++torn_frames_;
    reset();
  }
  last_byte_ = arrived;
  feed(bytes);
}

void FrameReceiver::feed_byte(std::uint8_t byte) {
  buffer_.push_back(byte);
  scan();
}

// Works on the buffer from its start. Dropping one byte at a time after a bad header means
// a frame that starts inside discarded bytes (e.g. `55 55 55 02 0F`) is still found.
void FrameReceiver::scan() {
  for (;;) {
    if (buffer_.empty()) return;
    if (buffer_[0] != kHeaderByte) {
      buffer_.erase(buffer_.begin());
      ++discarded_bytes_;
      continue;
    }
    if (buffer_.size() < 2) return;
    if (buffer_[1] != kHeaderByte) {
      buffer_.erase(buffer_.begin());
      ++discarded_bytes_;
      continue;
    }
    if (buffer_.size() < 3) return;
    const std::uint8_t len = buffer_[2];
    if (len < kMinLen || len > kMaxLen) {
      ++bad_lengths_;
      buffer_.erase(buffer_.begin());
      ++discarded_bytes_;
      continue;
    }
    const std::size_t total = 2u + len;
    if (buffer_.size() < total) return;
    Frame f;
    f.cmd = buffer_[3];
    f.data.assign(buffer_.begin() + 4, buffer_.begin() + static_cast<std::ptrdiff_t>(total));
    frames_.push_back(std::move(f));
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(total));
  }
}

std::optional<Frame> FrameReceiver::next() {
  if (frames_.empty()) return std::nullopt;
  Frame f = std::move(frames_.front());
  frames_.pop_front();
  return f;
}

void FrameReceiver::reset() {
  discarded_bytes_ += buffer_.size();
  buffer_.clear();
}

}  // namespace armctl::rc

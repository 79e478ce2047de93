// Streaming receiver for the serial form: hunts for `55 55`, reads LEN, takes LEN-1 more
// bytes. Bytes that cannot start a frame, and frames whose LEN is < 2 or cannot fit a
// 64-byte report, are discarded and the receiver resynchronises on the next `55 55`
// (spec "Frame"). Pure state machine: bytes in, frames out, no I/O.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "protocol/robot_commands/frame.hpp"

namespace armctl::rc {

class FrameReceiver {
 public:
  // Feed received bytes; complete frames are queued for next().
  void feed(std::span<const std::uint8_t> bytes);
  void feed_byte(std::uint8_t byte);

  // The oldest complete frame not yet taken.
  std::optional<Frame> next();
  std::size_t pending_frames() const { return frames_.size(); }

  // Bytes thrown away while hunting for a header or after a bad LEN.
  std::size_t discarded_bytes() const { return discarded_bytes_; }
  // Headers whose LEN was < 2 or too long for a report.
  std::size_t bad_lengths() const { return bad_lengths_; }
  // True while part of a frame is buffered (a caller may time it out with reset()).
  bool mid_frame() const { return !buffer_.empty(); }

  // Drop a partial frame (counted as discarded), e.g. after a read timeout.
  void reset();

 private:
  void scan();

  std::vector<std::uint8_t> buffer_;  // never more than one frame (<= 64 bytes)
  std::deque<Frame> frames_;
  std::size_t discarded_bytes_ = 0;
  std::size_t bad_lengths_ = 0;
};

}  // namespace armctl::rc

// Streaming receiver for the serial form: hunts for `55 55`, reads LEN, takes LEN-1 more
// bytes. Bytes that cannot start a frame, and frames whose LEN is < 2 or cannot fit a
// 64-byte report, are discarded and the receiver resynchronises on the next `55 55`
// (spec "Frame"). Pure state machine: bytes in, frames out, no I/O, no clock reads.
//
// Torn frames. Robot Commands has no timeout inside a frame: a sender that dies mid-frame
// leaves a partial frame that would join the next sender's bytes into something nobody
// sent (`55 55 08 03 01`, then seconds later `55 55 04 15 01 01` reads as a move of
// servo 4). Bytes fed with their arrival time are checked against the gap since the last
// byte: a partial frame older than `frame_gap(baud)` is dropped (counted as torn) before
// the new bytes are read. The gap is 20 byte times, and never under 50 ms: a USB-serial
// adapter holds received bytes for up to its latency timer (16 ms by default on FTDI
// chips) and a Linux sender can be descheduled for a few ms mid-write, so honest frames
// split across writes pause that long; a dead sender's successor comes far later.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "core/clock.hpp"
#include "protocol/robot_commands/frame.hpp"

namespace armctl::rc {

// The longest pause inside one frame that still joins its parts (see above).
Duration frame_gap(std::uint32_t baud);

class FrameReceiver {
 public:
  explicit FrameReceiver(Duration gap = frame_gap(9600)) : gap_(gap) {}
  void set_gap(Duration gap) { gap_ = gap; }
  Duration gap() const { return gap_; }

  // Feed received bytes; complete frames are queued for next(). With `arrived`, a partial
  // frame whose last byte came more than gap() earlier is dropped first (torn_frames()).
  void feed(std::span<const std::uint8_t> bytes);
  void feed(std::span<const std::uint8_t> bytes, TimePoint arrived);
  void feed_byte(std::uint8_t byte);

  // The oldest complete frame not yet taken.
  std::optional<Frame> next();
  std::size_t pending_frames() const { return frames_.size(); }

  // Bytes thrown away while hunting for a header or after a bad LEN.
  std::size_t discarded_bytes() const { return discarded_bytes_; }
  // Headers whose LEN was < 2 or too long for a report.
  std::size_t bad_lengths() const { return bad_lengths_; }
  // Partial frames dropped because their bytes stopped for longer than gap().
  std::size_t torn_frames() const { return torn_frames_; }
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
  std::size_t torn_frames_ = 0;
  Duration gap_;
  std::optional<TimePoint> last_byte_;
};

}  // namespace armctl::rc

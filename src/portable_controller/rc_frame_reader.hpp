// Robot Commands frames as the board receives them on a serial line (spec "Frame"): hunts
// for `55 55`, reads LEN, takes LEN-1 more bytes. LEN < 2 or LEN > 62 is discarded and the
// reader resynchronises on the next `55 55`. A partial frame whose bytes stop for longer
// than the gap is dropped (torn), so a host that died mid-frame can never join its bytes
// to the next host's request. The host side has the same rules in
// protocol/robot_commands/frame_receiver.hpp; this one is for the board (no heap, C++14).
#pragma once

#include <stdint.h>

namespace armctl {
namespace controller {

// The longest pause inside one frame that still joins its parts: 20 byte times and never
// under 50 ms (same as the host's rc::frame_gap).
uint32_t frame_gap_us(uint32_t baud);

class RcFrameReader {
 public:
  static const uint8_t max_length = 62;  // LEN: a frame must fit one 64-byte HID report

  explicit RcFrameReader(uint32_t gap_us = 50000) : gap_us_(gap_us) {}
  void set_gap_us(uint32_t gap_us) { gap_us_ = gap_us; }

  // True when this byte completed a frame; command()/data() describe it until the next call.
  bool on_byte(uint8_t byte, uint32_t now_us);

  uint8_t command() const { return command_; }
  const uint8_t* data() const { return data_; }
  uint8_t data_length() const { return static_cast<uint8_t>(length_ - 2); }

  uint16_t torn_frames() const { return torn_frames_; }
  uint16_t discarded_bytes() const { return discarded_bytes_; }

 private:
  enum class State : uint8_t { hunt_first, hunt_second, length, command, data };
  void discard(uint8_t count);

  uint32_t gap_us_;
  uint32_t last_byte_us_ = 0;
  State state_ = State::hunt_first;
  uint8_t length_ = 0;
  uint8_t command_ = 0;
  uint8_t received_ = 0;
  uint8_t data_[max_length];
  uint16_t torn_frames_ = 0;
  uint16_t discarded_bytes_ = 0;
};

}  // namespace controller
}  // namespace armctl

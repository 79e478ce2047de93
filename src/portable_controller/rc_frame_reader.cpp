#include "portable_controller/rc_frame_reader.hpp"

#include "portable_controller/counting.hpp"

namespace armctl {
namespace controller {

uint32_t frame_gap_us(uint32_t baud) {
  const uint32_t twenty_bytes = 200000000UL / baud;  // 20 bytes x 10 bits, in us
  return twenty_bytes > 50000UL ? twenty_bytes : 50000UL;
}

void RcFrameReader::discard(uint8_t count) {
  if (discarded_bytes_ <= 0xFFFFu - count) discarded_bytes_ = static_cast<uint16_t>(discarded_bytes_ + count);
}

bool RcFrameReader::on_byte(uint8_t byte, uint32_t now_us) {
  if (state_ != State::hunt_first && now_us - last_byte_us_ > gap_us_) {
    count_up(torn_frames_);
    state_ = State::hunt_first;
  }
  last_byte_us_ = now_us;
  switch (state_) {
    case State::hunt_first:
      if (byte == 0x55) state_ = State::hunt_second;
      else discard(1);
      return false;
    case State::hunt_second:
      if (byte == 0x55) {
        state_ = State::length;
      } else {
        discard(2);
        state_ = State::hunt_first;
      }
      return false;
    case State::length:
      if (byte < 2 || byte > max_length) {
        discard(3);
        // `55 55 55 ...`: the second and third 0x55 may be the real header.
        state_ = byte == 0x55 ? State::length : State::hunt_first;
        return false;
      }
      length_ = byte;
      state_ = State::command;
      return false;
    case State::command:
      command_ = byte;
      received_ = 0;
      if (length_ == 2) {
        state_ = State::hunt_first;
        return true;
      }
      state_ = State::data;
      return false;
    case State::data:
      data_[received_++] = byte;
      if (received_ == length_ - 2) {
        state_ = State::hunt_first;
        return true;
      }
      return false;
  }
  return false;
}

}  // namespace controller
}  // namespace armctl

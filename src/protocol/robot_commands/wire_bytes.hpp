// Little-endian field writing and reading for the message codec (internal helper).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace armctl::rc::wire {

inline void put_u8(std::vector<std::uint8_t>& out, std::uint8_t v) { out.push_back(v); }
inline void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

// Reads fields in order; running past the end sets `short_read` instead of reading garbage.
class Reader {
 public:
  explicit Reader(const std::vector<std::uint8_t>& data) : data_(data) {}
  std::uint8_t u8() {
    if (pos_ + 1 > data_.size()) {
      short_read_ = true;
      return 0;
    }
    return data_[pos_++];
  }
  std::uint16_t u16() {
    const std::uint8_t lo = u8();
    const std::uint8_t hi = u8();
    return static_cast<std::uint16_t>(lo | (hi << 8));
  }
  std::int16_t s16() { return static_cast<std::int16_t>(u16()); }
  std::int8_t s8() { return static_cast<std::int8_t>(u8()); }
  std::size_t remaining() const { return pos_ < data_.size() ? data_.size() - pos_ : 0; }
  bool short_read() const { return short_read_; }

 private:
  const std::vector<std::uint8_t>& data_;
  std::size_t pos_ = 0;
  bool short_read_ = false;
};

}  // namespace armctl::rc::wire

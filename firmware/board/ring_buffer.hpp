// Fixed-capacity single-producer/single-consumer ring buffer for ISR <-> main loop hand-off.
// One side only writes `head_`, the other only writes `tail_`; both are one byte, so every
// index access is atomic on the AVR and no interrupt masking is needed.
#pragma once

#include <stdint.h>

namespace board {

template <typename T, uint8_t Capacity>
class RingBuffer {
  static_assert(Capacity >= 2 && Capacity <= 128 && (Capacity & (Capacity - 1)) == 0,
                "capacity must be a power of two, at most 128");

 public:
  bool push(T value) {
    const uint8_t head = head_;
    const uint8_t next = static_cast<uint8_t>((head + 1) & (Capacity - 1));
    if (next == tail_) return false;  // full: the caller counts the loss
    items_[head] = value;
    head_ = next;
    return true;
  }

  bool pop(T* value) {
    const uint8_t tail = tail_;
    if (tail == head_) return false;
    *value = items_[tail];
    tail_ = static_cast<uint8_t>((tail + 1) & (Capacity - 1));
    return true;
  }

  bool empty() const { return head_ == tail_; }
  bool full() const { return static_cast<uint8_t>((head_ + 1) & (Capacity - 1)) == tail_; }
  void clear() { tail_ = head_; }  // consumer side only

 private:
  T items_[Capacity];
  volatile uint8_t head_ = 0;
  volatile uint8_t tail_ = 0;
};

}  // namespace board

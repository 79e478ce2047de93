// How long the master waits for each word: the word's wire time x a margin, plus a
// turnaround for the joint (and, on remote links, the link) to react. Derived from the baud
// so that 9600 and 115200 buses both fail fast and never wait forever.
#pragma once

#include <chrono>
#include <cstdint>

#include "core/clock.hpp"

namespace armctl::joint_bus {

struct BusTiming {
  int word_margin = 4;                                // wire times of one word allowed
  Duration turnaround = std::chrono::milliseconds(2);  // joint reaction + link latency

  // The longest wait for one 2-byte word at `baud`.
  Duration word_timeout(std::uint32_t baud) const {
    return wire_time(2, baud) * word_margin + turnaround;
  }
};

}  // namespace armctl::joint_bus

// Test helper: one joint bus transaction done byte by byte on a JointBusLink, the way the
// spec's transaction goes (READY, COMMAND, DATA, RESPONSE, select low, STATUS). Deliberately
// tiny and local: these tests must not depend on the bus master (devices/joint_bus).
#pragma once

#include <cstdint>
#include <optional>

#include "portable/joint_bus_codes.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::joint_sim::testing {

struct Reply {
  std::optional<std::int16_t> ready;
  std::optional<std::int16_t> response;
  std::optional<std::int16_t> status;
};

inline Duration word_timeout(const transport::JointBusLink& link) {
  return wire_time(2, link.baud()) * 4 + std::chrono::milliseconds(5);
}

inline std::optional<std::int16_t> read_word(transport::JointBusLink& link) {
  const auto lo = link.read_byte(link.clock().now() + word_timeout(link));
  if (!lo) return std::nullopt;
  const auto hi = link.read_byte(link.clock().now() + word_timeout(link));
  if (!hi) return std::nullopt;
  return joint_bus::word_from(*lo, *hi);
}

inline void write_word(transport::JointBusLink& link, std::int16_t w) {
  const std::uint8_t bytes[2] = {joint_bus::word_low(w), joint_bus::word_high(w)};
  link.write(bytes);
}

// Runs `command` on `joint`. Stops early (fields left empty) where the joint stays silent.
inline Reply transact(transport::JointBusLink& link, int joint, std::int16_t command,
                      std::int16_t data = 0) {
  const joint_bus::CommandShape shape = joint_bus::command_shape(command);
  Reply r;
  link.drain();
  link.set_select(joint, true);
  r.ready = read_word(link);
  if (r.ready && *r.ready == joint) {
    write_word(link, command);
    if (shape.takes_data) write_word(link, data);
    link.flush();
    if (shape.returns_value) r.response = read_word(link);
  }
  link.set_select(joint, false);
  if (r.ready && *r.ready == joint) r.status = read_word(link);
  return r;
}

inline bool succeeded(const Reply& r, std::int16_t command) {
  return r.status && *r.status == joint_bus::success_status(command);
}

}  // namespace armctl::joint_sim::testing

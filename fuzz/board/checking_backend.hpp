// An in-memory arm for fuzzing the Board: six servos 1..6 with position limits, and a
// trap for every call that a correctly validating Board must never make.
#pragma once

#include <array>
#include <cstdlib>

#include "devices/rc_board/arm_backend.hpp"

namespace armctl::fuzz {

class CheckingBackend final : public rc_board::ArmBackend {
 public:
  std::span<const rc_board::ServoId> servos() const override { return ids_; }
  rc_board::PositionRange position_range(rc_board::ServoId s) const override {
    return limits_[index(s)];
  }
  void advance_to(TimePoint now) override {
    if (now < now_) std::abort();  // time went backwards
    now_ = now;
  }
  Result<Duration> move(std::span<const rc_board::ServoTarget> targets, Duration time,
                        TimePoint now) override {
    if (now < now_ || targets.empty() || time < Duration::zero()) std::abort();
    for (const auto& t : targets) {
      if (!t.position) std::abort();  // "leave alone" must have been dropped
      if (!position_range(t.servo).contains(*t.position)) std::abort();  // out-of-range move
      positions_[index(t.servo)] = static_cast<std::int16_t>(*t.position);
    }
    return time;
  }
  std::int16_t position(rc_board::ServoId s) const override { return positions_[index(s)]; }
  void torque_off(std::span<const rc_board::ServoId> ids) override {
    for (auto id : ids) index(id);
  }
  void halt(TimePoint now) override { advance_to(now); }
  std::uint16_t battery_millivolts() const override { return 7500; }
  void adjust_offset(rc_board::ServoId s, std::int8_t offset) override {
    if (offset < -125 || offset > 125) std::abort();
    offsets_[index(s)] = offset;
  }
  Status save_offsets(std::span<const rc_board::ServoId> ids) override {
    for (auto id : ids) index(id);
    return Ok{};
  }
  std::int8_t offset(rc_board::ServoId s) const override { return offsets_[index(s)]; }
  void set_mode(rc_board::ServoId s, rc_board::ServoMode, std::int16_t speed, TimePoint) override {
    index(s);
    if (speed < -1000 || speed > 1000) std::abort();
  }
  rc_board::BusServoInfoReply bus_servo_info() const override {
    return rc::bus_servo_info_reply(limits_info_, 0, 500, 30, 7500);
  }
  Status write_bus_servo_info(const rc_board::BusServoLimits& l) override {
    if (l.position_min > l.position_max || l.position_max > 1000) std::abort();
    if (!has_servo(l.servo)) return Error{ErrorKind::device, "no such servo"};
    limits_[index(l.servo)] = {l.position_min, l.position_max};
    limits_info_ = l;
    return Ok{};
  }

 private:
  std::size_t index(rc_board::ServoId s) const {
    if (s < 1 || s > 6) std::abort();  // the Board let an absent servo through
    return s - 1U;
  }
  std::array<rc_board::ServoId, 6> ids_{1, 2, 3, 4, 5, 6};
  std::array<rc_board::PositionRange, 6> limits_{};
  std::array<std::int16_t, 6> positions_{500, 500, 500, 500, 500, 500};
  std::array<std::int8_t, 6> offsets_{};
  rc_board::BusServoLimits limits_info_{};
  TimePoint now_{};
};

}  // namespace armctl::fuzz

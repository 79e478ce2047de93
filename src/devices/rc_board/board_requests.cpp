// The Board's handler for each Robot Commands request, reached from Board::dispatch once the
// frame has decoded. Each checks what only this arm can know (servos present, their
// ranges), then acts, replies and counts: a refused request changes nothing.
#include <algorithm>
#include <vector>

#include <fmt/core.h>

#include "devices/rc_board/board.hpp"

namespace armctl::rc_board {

// ------------------------------------------------------------------------------ servos

void Board::on(const rc::MultiServoMove& m, TimePoint now) {
  std::vector<ServoTarget> targets;
  for (const ServoTarget& t : m.targets) {
    if (!arm_.has_servo(t.servo))
      return reject(&BoardStats::unknown_servo,
                    fmt::format("MultiServoMove: servo {} is not present: frame ignored", t.servo));
    if (!t.position) continue;  // 0xFF00: leave this servo alone
    const PositionRange range = arm_.position_range(t.servo);
    if (!range.contains(*t.position))
      return reject(&BoardStats::out_of_range,
                    fmt::format("MultiServoMove: servo {} position {} outside its range {}..{}: "
                                "frame ignored",
                                t.servo, *t.position, range.min, range.max));
    targets.push_back(t);
  }
  if (!targets.empty()) {
    auto moved = arm_.move(targets, std::chrono::milliseconds(m.time_ms), now);
    if (!moved)
      return reject(&BoardStats::refused_moves, "MultiServoMove refused: " + moved.error().message);
  }
  ++stats_.handled;
}

void Board::on(const rc::MultiServoOff& m, TimePoint) {
  if (!all_present(m.servos, "MultiServoOff")) return;
  ++stats_.handled;
  arm_.torque_off(m.servos);
}

void Board::on(const rc::ServoPositionRead& m, TimePoint) {
  if (!all_present(m.servos, "ServoPositionRead")) return;
  rc::ServoPositionReply r;
  for (std::uint8_t id : m.servos) {
    const auto position = arm_.read_position(id);
    if (!position) return no_answer("ServoPositionRead", id);
    r.positions.push_back({id, *position});
  }
  ++stats_.handled;
  reply(r);
}

void Board::on(const rc::ServoSpeed& m, TimePoint now) {
  const std::uint8_t ids[] = {m.servo};
  if (!all_present(ids, "ServoSpeed")) return;
  // Motor mode: the u16 is a signed speed (two's complement), -1000..1000.
  const auto speed = static_cast<std::int16_t>(m.milliseconds);
  const bool motor = m.mode == ServoMode::motor;
  if (motor && (speed < -rc::kMotorSpeedMax || speed > rc::kMotorSpeedMax))
    return reject(&BoardStats::out_of_range,
                  fmt::format("ServoSpeed: motor speed {} not in -{}..{}", speed,
                              rc::kMotorSpeedMax, rc::kMotorSpeedMax));
  ++stats_.handled;
  arm_.set_mode(m.servo, m.mode, motor ? speed : std::int16_t{0}, now);
}

void Board::on(const rc::GetBatteryVoltage&, TimePoint) {
  ++stats_.handled;
  reply(rc::BatteryVoltageReply{arm_.battery_millivolts()});
}

// ----------------------------------------------------------------------------- offsets

void Board::on(const rc::ServoOffsetAdjust& m, TimePoint) {
  const std::uint8_t ids[] = {m.servo};
  if (!all_present(ids, "ServoOffsetAdjust")) return;
  if (m.offset < rc::kOffsetMin || m.offset > rc::kOffsetMax)
    return reject(&BoardStats::out_of_range,
                  fmt::format("ServoOffsetAdjust: offset {} not in {}..{}", m.offset,
                              rc::kOffsetMin, rc::kOffsetMax));
  ++stats_.handled;
  arm_.adjust_offset(m.servo, static_cast<std::int8_t>(m.offset));
}

void Board::on(const rc::ServoOffsetWrite& m, TimePoint) {
  if (!all_present(m.servos, "ServoOffsetWrite")) return;
  if (auto saved = arm_.save_offsets(m.servos); !saved)
    return reject(&BoardStats::refused,
                  "ServoOffsetWrite: offsets could not be saved: " + saved.error().message);
  ++stats_.handled;
}

void Board::on(const rc::ServoOffsetRead& m, TimePoint) {
  if (!all_present(m.servos, "ServoOffsetRead")) return;
  rc::ServoOffsetReply r;
  for (std::uint8_t id : m.servos) {
    const auto offset = arm_.read_offset(id);
    if (!offset) return no_answer("ServoOffsetRead", id);
    r.offsets.push_back({id, *offset});
  }
  ++stats_.handled;
  reply(r);
}

// ------------------------------------------------------------------- bus servo settings

void Board::on(const rc::BusServoInfoWrite& m, TimePoint) {
  if (m.position_min > m.position_max || m.position_max > rc::kPositionMax ||
      m.millivolts_min > m.millivolts_max || m.millivolts_min < rc::kMillivoltsMin ||
      m.millivolts_max > rc::kMillivoltsMax || m.temp_max < rc::kTempMaxMin ||
      m.temp_max > rc::kTempMaxMax || m.led_status > 1 || m.led_warning > 7)
    return reject(&BoardStats::out_of_range,
                  "BusServoInfoWrite: limits out of range (positions 0..1000 min<=max, "
                  "millivolts 4500..12000 min<=max, temp 50..100, led_status 0..1, "
                  "led_warning 0..7): frame ignored");
  if (auto written = arm_.write_bus_servo_info(m); !written)
    return reject(written.error().kind == ErrorKind::device ? &BoardStats::unknown_servo
                                                            : &BoardStats::refused,
                  fmt::format("BusServoInfoWrite: servo {} not accepted by this arm: {}", m.servo,
                              written.error().message));
  ++stats_.handled;
}

void Board::on(const rc::BusServoInfoRead&, TimePoint) {
  const auto info = arm_.read_bus_servo_info();
  if (!info) return no_answer("BusServoInfoRead", std::nullopt);
  ++stats_.handled;
  reply(*info);
}

void Board::no_answer(const char* request, std::optional<ServoId> servo) {
  reject(&BoardStats::no_answer,
         fmt::format("{}: {} did not answer usably (no servo answers it, or several did and their "
                     "replies collided): no reply",
                     request, servo ? fmt::format("servo {}", *servo) : std::string("the servo bus")));
}

// --------------------------------------------------------------------- group download

void Board::download_failed(const Error& e) { reject(&BoardStats::download_rejected, e.message); }

void Board::ack(std::uint8_t sub) {
  ++stats_.handled;
  reply(rc::GroupDownloadAck{sub});
}

void Board::on(const rc::GroupDownloadBegin& m, TimePoint) {
  if (auto s = download_.begin(m); !s) return download_failed(s.error());
  ack(1);
}

void Board::on(const rc::GroupDownloadServoCount& m, TimePoint) {
  if (auto s = download_.servo_count(m, arm_); !s) return download_failed(s.error());
  ack(2);
}

void Board::on(const rc::GroupDownloadBlocks& m, TimePoint) {
  if (auto s = download_.blocks(m); !s) return download_failed(s.error());
  ack(3);
}

void Board::on(const rc::GroupDownloadAction& m, TimePoint) {
  if (auto s = download_.action(m, arm_); !s) return download_failed(s.error());
  ack(4);
}

void Board::on(const rc::GroupDownloadEnd& m, TimePoint) {
  auto group = download_.end(m);
  if (!group) return download_failed(group.error());
  // The group becomes visible only once it is durably stored.
  if (auto s = store_.save(m.group, std::move(group).value()); !s)
    return reject(&BoardStats::refused, fmt::format("GroupDownload: cannot store group {}: {}",
                                                    m.group, s.error().message));
  ack(5);
}

// ----------------------------------------------------------------- groups: play, erase

void Board::on(const rc::GroupRun& m, TimePoint now) {
  const ActionGroup* group = store_.find(m.group);
  if (!group)
    return reject(&BoardStats::refused,
                  fmt::format("GroupRun: group {} is empty: frame ignored", m.group));
  ++stats_.handled;
  if (player_.running()) notify_stopped();  // the new run replaces the old one
  player_.start(m.group, *group, m.count, now);
  reply(rc::GroupNotification{rc::GroupEventKind::started, m.group, m.count});
  advance_to(now);  // the first action starts now
}

void Board::on(const rc::GroupStop&, TimePoint now) {
  ++stats_.handled;
  player_.stop();
  arm_.halt(now);
  notify_stopped();  // also when idle: a host waiting for CMD 7 gets its answer
}

void Board::on(const rc::GroupErase& m, TimePoint now) {
  const Status s = m.group == rc::kAllGroups ? store_.erase_all() : store_.erase(m.group);
  if (!s)
    return reject(&BoardStats::refused,
                  fmt::format("GroupErase: {}: frame ignored", s.error().message));
  ++stats_.handled;
  const auto running = player_.group();
  if (running && (m.group == rc::kAllGroups || m.group == *running)) {
    player_.stop();
    arm_.halt(now);
    notify_stopped();
  }
  reply(rc::GroupEraseReply{});
}

void Board::on(const rc::GroupSpeed& m, TimePoint) {
  ++stats_.handled;
  if (m.group == rc::kAllGroups)
    std::fill(std::begin(speeds_), std::end(speeds_), m.percent);
  else
    speeds_[m.group] = m.percent;
}

}  // namespace armctl::rc_board

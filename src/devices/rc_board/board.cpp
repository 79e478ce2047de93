#include "devices/rc_board/board.hpp"

#include <algorithm>
#include <type_traits>
#include <variant>
#include <vector>

#include <fmt/core.h>

#include "protocol/robot_commands/command_codes.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::rc_board {
namespace {

// The codec checks structure and the spec's fixed ranges; which servos exist is this
// arm's business, checked here so that an absent servo is counted as such.
constexpr rc::ServoRange kAnyServo{0, 255};

constexpr int kMotorSpeedLimit = 1000;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace

Board::Board(ArmBackend& arm, GroupStore& store, const Clock& clock, Output output)
    : arm_(arm), store_(store), clock_(clock), output_(std::move(output)) {
  std::fill(std::begin(speeds_), std::end(speeds_), std::uint16_t{100});
  last_now_ = clock_.now();
}

BoardStats Board::stats() const {
  BoardStats s = stats_;
  s.discarded_bytes = receiver_.discarded_bytes();
  s.bad_lengths = receiver_.bad_lengths();
  s.torn_frames = receiver_.torn_frames();
  return s;
}

void Board::receive(std::span<const std::uint8_t> bytes) {
  receiver_.feed(bytes, clock_.now());  // a partial frame left by a dead host is dropped
  while (auto frame = receiver_.next()) handle(*frame);
}

void Board::poll() {
  advance_to(clock_.now());
}

void Board::advance_to(TimePoint now) {
  now = std::max(now, last_now_);  // a backend never sees time go backwards
  // Play every action that fell due since the last call at its own instant.
  while (auto due = player_.next_event()) {
    if (*due > now) break;
    arm_.advance_to(*due);
    auto group = player_.group();
    const std::size_t refused_before = player_.moves_refused();
    auto finished = player_.step(arm_, speeds_[*group]);
    if (player_.moves_refused() != refused_before)
      reject(&BoardStats::refused_moves, "GroupRun: " + player_.last_refusal());
    if (finished) {
      auto frame = rc::encode(rc::BoardMessage{
          rc::GroupNotification{rc::GroupEventKind::finished, finished->group, finished->count}});
      if (frame) send(*frame);
    }
  }
  arm_.advance_to(now);
  last_now_ = now;
}

void Board::send(const rc::Frame& frame) {
  if (output_) output_(frame);
}

void Board::notify_stopped() {
  auto frame = rc::encode(rc::BoardMessage{
      rc::GroupNotification{rc::GroupEventKind::stopped, std::nullopt, std::nullopt}});
  if (frame) send(*frame);
}

void Board::reject(std::size_t BoardStats::*counter, std::string message) {
  ++(stats_.*counter);
  last_rejection_ = std::move(message);
  if (log_) log_(last_rejection_);
}

void Board::handle(const rc::Frame& frame) {
  ++stats_.frames;
  advance_to(clock_.now());
  dispatch(frame, last_now_);
}

void Board::dispatch(const rc::Frame& frame, TimePoint now) {
  if (!rc::command_from_byte(frame.cmd)) {
    reject(&BoardStats::unknown_command,
           fmt::format("unknown CMD {} (0x{:02X}): frame ignored", frame.cmd, frame.cmd));
    return;
  }
  auto request = rc::decode_request(frame, kAnyServo);
  if (!request) {
    if (frame.cmd == static_cast<std::uint8_t>(rc::Command::GroupDownload) &&
        download_.in_progress()) {
      // A malformed part of a download makes the whole download inconsistent.
      download_.abandon();
      reject(&BoardStats::download_rejected,
             request.error().message + " (download abandoned; stored group unchanged)");
      return;
    }
    reject(&BoardStats::invalid_frame, request.error().message + ": frame ignored");
    return;
  }

  // Checks shared by the commands that list servos.
  auto all_present = [&](const auto& ids, const char* what) {
    for (std::uint8_t id : ids) {
      if (!arm_.has_servo(id)) {
        reject(&BoardStats::unknown_servo,
               fmt::format("{}: servo {} is not present: frame ignored", what, id));
        return false;
      }
    }
    return true;
  };
  auto reply = [&](const rc::BoardMessage& message) {
    auto encoded = rc::encode(message);
    if (encoded) send(*encoded);
  };
  auto download_failed = [&](const Error& e) { reject(&BoardStats::download_rejected, e.message); };
  auto ack = [&](std::uint8_t sub) {
    ++stats_.handled;
    reply(rc::GroupDownloadAck{sub});
  };

  std::visit(
      Overloaded{
          [&](const rc::MultiServoMove& m) {
            std::vector<ServoTarget> targets;
            for (const rc::ServoTarget& t : m.targets) {
              if (!arm_.has_servo(t.servo))
                return reject(
                    &BoardStats::unknown_servo,
                    fmt::format("MultiServoMove: servo {} is not present: frame ignored", t.servo));
              if (!t.position) continue;  // 0xFF00: leave this servo alone
              PositionRange range = arm_.position_range(t.servo);
              if (!range.contains(*t.position))
                return reject(&BoardStats::out_of_range,
                              fmt::format("MultiServoMove: servo {} position {} outside its "
                                          "range {}..{}: frame ignored",
                                          t.servo, *t.position, range.min, range.max));
              targets.push_back({t.servo, *t.position});
            }
            if (targets.empty()) {
              ++stats_.handled;
              return;
            }
            auto moved = arm_.move(targets, std::chrono::milliseconds(m.time_ms), now);
            if (!moved)
              return reject(&BoardStats::refused_moves,
                            "MultiServoMove refused: " + moved.error().message);
            ++stats_.handled;
          },
          [&](const rc::GroupDownloadBegin& m) {
            if (auto s = download_.begin(m); !s) return download_failed(s.error());
            ack(1);
          },
          [&](const rc::GroupDownloadServoCount& m) {
            if (auto s = download_.servo_count(m, arm_); !s) return download_failed(s.error());
            ack(2);
          },
          [&](const rc::GroupDownloadBlocks& m) {
            if (auto s = download_.blocks(m); !s) return download_failed(s.error());
            ack(3);
          },
          [&](const rc::GroupDownloadAction& m) {
            if (auto s = download_.action(m, arm_); !s) return download_failed(s.error());
            ack(4);
          },
          [&](const rc::GroupDownloadEnd& m) {
            auto group = download_.end(m);
            if (!group) return download_failed(group.error());
            // The group becomes visible only once it is durably stored.
            if (auto s = store_.save(m.group, std::move(group).value()); !s)
              return reject(&BoardStats::refused,
                            fmt::format("GroupDownload: cannot store group {}: {}", m.group,
                                        s.error().message));
            ack(5);
          },
          [&](const rc::GroupRun& m) {
            const ActionGroup* group = store_.find(m.group);
            if (!group)
              return reject(&BoardStats::refused,
                            fmt::format("GroupRun: group {} is empty: frame ignored", m.group));
            ++stats_.handled;
            if (player_.running()) notify_stopped();  // the new run replaces the old one
            player_.start(m.group, *group, m.count, now);
            reply(rc::GroupNotification{rc::GroupEventKind::started, m.group, m.count});
            advance_to(now);  // the first action starts now
          },
          [&](const rc::GroupStop&) {
            ++stats_.handled;
            player_.stop();
            arm_.halt(now);
            notify_stopped();  // also when idle: a host waiting for CMD 7 gets its answer
          },
          [&](const rc::GroupErase& m) {
            Status s = m.group == kAllGroups ? store_.erase_all() : store_.erase(m.group);
            if (!s)
              return reject(&BoardStats::refused,
                            fmt::format("GroupErase: {}: frame ignored", s.error().message));
            ++stats_.handled;
            auto running = player_.group();
            if (running && (m.group == kAllGroups || m.group == *running)) {
              player_.stop();
              arm_.halt(now);
              notify_stopped();
            }
            reply(rc::GroupEraseReply{});
          },
          [&](const rc::GroupSpeed& m) {
            ++stats_.handled;
            if (m.group == kAllGroups)
              std::fill(std::begin(speeds_), std::end(speeds_), m.percent);
            else
              speeds_[m.group] = m.percent;
          },
          [&](const rc::GetBatteryVoltage&) {
            ++stats_.handled;
            reply(rc::BatteryVoltageReply{arm_.battery_millivolts()});
          },
          [&](const rc::MultiServoOff& m) {
            if (!all_present(m.servos, "MultiServoOff")) return;
            ++stats_.handled;
            arm_.torque_off(m.servos);
          },
          [&](const rc::ServoPositionRead& m) {
            if (!all_present(m.servos, "ServoPositionRead")) return;
            ++stats_.handled;
            rc::ServoPositionReply r;
            for (std::uint8_t id : m.servos) r.positions.push_back({id, arm_.position(id)});
            reply(r);
          },
          [&](const rc::ServoOffsetWrite& m) {
            if (!all_present(m.servos, "ServoOffsetWrite")) return;
            if (auto saved = arm_.save_offsets(m.servos); !saved)
              return reject(&BoardStats::refused, "ServoOffsetWrite: offsets could not be saved: " +
                                                      saved.error().message);
            ++stats_.handled;
          },
          [&](const rc::ServoOffsetRead& m) {
            if (!all_present(m.servos, "ServoOffsetRead")) return;
            ++stats_.handled;
            rc::ServoOffsetReply r;
            for (std::uint8_t id : m.servos) r.offsets.push_back({id, arm_.offset(id)});
            reply(r);
          },
          [&](const rc::ServoOffsetAdjust& m) {
            const std::uint8_t ids[] = {m.servo};
            if (!all_present(ids, "ServoOffsetAdjust")) return;
            if (m.offset < rc::kOffsetMin || m.offset > rc::kOffsetMax)
              return reject(&BoardStats::out_of_range,
                            fmt::format("ServoOffsetAdjust: offset {} not in -125..125", m.offset));
            ++stats_.handled;
            arm_.adjust_offset(m.servo, static_cast<std::int8_t>(m.offset));
          },
          [&](const rc::ServoSpeed& m) {
            const std::uint8_t ids[] = {m.servo};
            if (!all_present(ids, "ServoSpeed")) return;
            // Motor mode: the u16 is a signed speed (two's complement), -1000..1000.
            auto speed = static_cast<std::int16_t>(m.milliseconds);
            if (m.mode == rc::ServoMode::motor &&
                (speed < -kMotorSpeedLimit || speed > kMotorSpeedLimit))
              return reject(&BoardStats::out_of_range,
                            fmt::format("ServoSpeed: motor speed {} not in -1000..1000", speed));
            ++stats_.handled;
            arm_.set_mode(m.servo,
                          m.mode == rc::ServoMode::motor ? ServoMode::motor : ServoMode::servo,
                          m.mode == rc::ServoMode::motor ? speed : std::int16_t{0}, now);
          },
          [&](const rc::BusServoInfoWrite& m) {
            BusServoLimits l{m.servo,          m.position_min, m.position_max, m.millivolts_min,
                             m.millivolts_max, m.temp_max,     m.led_status,   m.led_warning};
            if (l.position_min > l.position_max || l.position_max > rc::kPositionMax ||
                l.millivolts_min > l.millivolts_max || l.millivolts_min < rc::kMillivoltsMin ||
                l.millivolts_max > rc::kMillivoltsMax || l.temp_max < rc::kTempMaxMin ||
                l.temp_max > rc::kTempMaxMax || l.led_status > 1 || l.led_warning > 7)
              return reject(&BoardStats::out_of_range,
                            "BusServoInfoWrite: limits out of range (positions 0..1000 min<=max, "
                            "millivolts 4500..12000 min<=max, temp 50..100, led_status 0..1, "
                            "led_warning 0..7): frame ignored");
            if (auto written = arm_.write_bus_servo_info(l); !written)
              return reject(written.error().kind == ErrorKind::device ? &BoardStats::unknown_servo
                                                                      : &BoardStats::refused,
                            fmt::format("BusServoInfoWrite: servo {} not accepted by this arm: {}",
                                        m.servo, written.error().message));
            ++stats_.handled;
          },
          [&](const rc::BusServoInfoRead&) {
            ++stats_.handled;
            BusServoInfo i = arm_.bus_servo_info();
            reply(rc::BusServoInfoReply{i.limits.servo, i.limits.position_min,
                                        i.limits.position_max, i.limits.millivolts_min,
                                        i.limits.millivolts_max, i.limits.temp_max,
                                        i.limits.led_status, i.limits.led_warning, i.offset,
                                        i.position, i.temp, i.millivolts});
          },
      },
      *request);
}

}  // namespace armctl::rc_board

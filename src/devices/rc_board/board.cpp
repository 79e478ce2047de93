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

void Board::stop_playback(const std::string& why) {
  const auto group = player_.group();
  if (!group) return;
  player_.stop();
  if (log_) log_(fmt::format("group {} stopped: {}", *group, why));
  notify_stopped();
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
  // One handler per request (board_requests.cpp).
  std::visit([&](const auto& message) { on(message, now); }, *request);
}

bool Board::all_present(std::span<const std::uint8_t> ids, const char* what) {
  for (std::uint8_t id : ids) {
    if (!arm_.has_servo(id)) {
      reject(&BoardStats::unknown_servo,
             fmt::format("{}: servo {} is not present: frame ignored", what, id));
      return false;
    }
  }
  return true;
}

void Board::reply(const rc::BoardMessage& message) {
  if (auto encoded = rc::encode(message)) send(*encoded);
}

}  // namespace armctl::rc_board

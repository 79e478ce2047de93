// RcLinks on simulated time for SDK tests: a scripted fake board and the emulated xArm.
// Waiting in receive() is what advances the SimClock; nothing sleeps.
#pragma once

#include <algorithm>
#include <deque>
#include <functional>
#include <memory>
#include <vector>

#include "core/clock.hpp"
#include "devices/robot_commands/rc_link.hpp"
#include "devices/xarm_emulator/xarm_emulator.hpp"

namespace armctl::robot_commands::testing {

// A fake board: `respond` sees each frame the host sends and returns frames to send back,
// each after a delay (from the moment of sending).
class ScriptedLink final : public RcLink {
 public:
  struct Timed {
    Duration after;
    rc::Frame frame;
  };
  using Responder = std::function<std::vector<Timed>(const rc::Frame&)>;

  explicit ScriptedLink(Responder respond = {}) : respond_(std::move(respond)) {}

  void send(const rc::Frame& frame) override {
    sent.push_back(frame);
    if (!respond_) return;
    for (auto& t : respond_(frame)) inject(t.frame, t.after);
  }
  std::optional<rc::Frame> receive(TimePoint deadline) override {
    if (!pending_.empty() && pending_.front().first <= deadline) {
      clock_.advance_to(pending_.front().first);
      rc::Frame f = pending_.front().second;
      pending_.pop_front();
      return f;
    }
    clock_.advance_to(deadline);
    return std::nullopt;
  }
  const Clock& clock() const override { return clock_; }
  SimClock& sim_clock() { return clock_; }
  std::string describe() const override { return "scripted board"; }

  // A frame from the board `after` from now (kept in time order).
  void inject(const rc::Frame& f, Duration after = Duration{0}) {
    const TimePoint at = clock_.now() + after;
    auto it = pending_.begin();
    while (it != pending_.end() && it->first <= at) ++it;
    pending_.insert(it, {at, f});
  }

  std::vector<rc::Frame> sent;

 private:
  SimClock clock_;
  Responder respond_;
  std::deque<std::pair<TimePoint, rc::Frame>> pending_;
};

// The emulated xArm (board helper's XarmEmulator) in process, on a SimClock. Frames go
// through the serial form so the board's own receiver is exercised too. With a baud set,
// the line is modelled: each frame reaches the other end its wire time after the line is
// free (one line each way), as on a serial port; without one, frames arrive at once.
class EmulatedLink final : public RcLink {
 public:
  explicit EmulatedLink(std::uint32_t baud = 0, xarm::XarmEmulatorOptions options = {})
      : baud_(baud), emulator_(clock_, std::move(options), [this](const rc::Frame& f) { from_board(f); }) {}

  void send(const rc::Frame& frame) override {
    sent.push_back(frame);
    if (deaf_) return;
    auto bytes = rc::encode_frame(frame);
    if (baud_ == 0) {
      emulator_.receive(bytes);
      return;
    }
    to_board_free_ = std::max(to_board_free_, clock_.now()) + wire_time(bytes.size(), baud_);
    to_board_.push_back({to_board_free_, std::move(bytes)});
  }
  std::optional<rc::Frame> receive(TimePoint deadline) override {
    // Each round either returns or moves time strictly forward (to the next frame's arrival,
    // the board's next playback instant or the deadline), so this always ends.
    for (;;) {
      while (!to_board_.empty() && to_board_.front().first <= clock_.now()) {
        emulator_.receive(to_board_.front().second);
        to_board_.pop_front();
      }
      if (!out_.empty() && out_.front().first <= clock_.now()) {
        rc::Frame f = out_.front().second;
        out_.pop_front();
        return f;
      }
      if (clock_.now() >= deadline) return std::nullopt;
      TimePoint step = deadline;
      auto sooner = [&](TimePoint t) {
        if (t > clock_.now() && t < step) step = t;
      };
      if (const auto wake = emulator_.board().next_wakeup()) sooner(*wake);
      if (!to_board_.empty()) sooner(to_board_.front().first);
      if (!out_.empty()) sooner(out_.front().first);
      clock_.advance_to(step);
      emulator_.poll();
    }
  }
  const Clock& clock() const override { return clock_; }
  std::string describe() const override { return "emulated xArm (SimClock)"; }
  Duration frame_time(std::size_t serial_bytes) const override {
    return baud_ ? wire_time(serial_bytes, baud_) : RcLink::frame_time(serial_bytes);
  }

  xarm::XarmEmulator& emulator() { return emulator_; }
  SimClock& sim_clock() { return clock_; }
  // A pulled cable: from now on nothing sent reaches the board (nor is answered).
  void set_deaf(bool deaf) { deaf_ = deaf; }
  std::vector<rc::Frame> sent;

 private:
  void from_board(const rc::Frame& f) {
    TimePoint at = clock_.now();
    if (baud_) at = from_board_free_ = std::max(from_board_free_, at) + wire_time(rc::encode_frame(f).size(), baud_);
    out_.push_back({at, f});
  }

  std::uint32_t baud_;
  bool deaf_ = false;
  SimClock clock_;
  std::deque<std::pair<TimePoint, std::vector<std::uint8_t>>> to_board_;
  std::deque<std::pair<TimePoint, rc::Frame>> out_;
  TimePoint to_board_free_{}, from_board_free_{};
  xarm::XarmEmulator emulator_;
};

}  // namespace armctl::robot_commands::testing

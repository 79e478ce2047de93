// RcLinks on simulated time for SDK tests: a scripted fake board and the emulated xArm.
// Waiting in receive() is what advances the SimClock; nothing sleeps.
#pragma once

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
// through the serial form so the board's own receiver is exercised too.
class EmulatedLink final : public RcLink {
 public:
  EmulatedLink()
      : emulator_(clock_, xarm::XarmEmulatorOptions{},
                  [this](const rc::Frame& f) { out_.push_back(f); }) {}

  void send(const rc::Frame& frame) override {
    sent.push_back(frame);
    emulator_.receive(rc::encode_frame(frame));
  }
  std::optional<rc::Frame> receive(TimePoint deadline) override {
    // Each round either returns or moves time strictly forward (to the board's next
    // playback instant or to the deadline), so this always ends.
    for (;;) {
      if (!out_.empty()) {
        rc::Frame f = out_.front();
        out_.pop_front();
        return f;
      }
      if (clock_.now() >= deadline) return std::nullopt;
      TimePoint step = deadline;
      const auto wake = emulator_.board().next_wakeup();
      if (wake && *wake > clock_.now() && *wake < deadline) step = *wake;
      clock_.advance_to(step);
      emulator_.poll();
    }
  }
  const Clock& clock() const override { return clock_; }
  std::string describe() const override { return "emulated xArm (SimClock)"; }

  xarm::XarmEmulator& emulator() { return emulator_; }
  SimClock& sim_clock() { return clock_; }
  std::vector<rc::Frame> sent;

 private:
  SimClock clock_;
  std::deque<rc::Frame> out_;
  xarm::XarmEmulator emulator_;
};

}  // namespace armctl::robot_commands::testing

// A fake xArm board behind the HID seam, behaving the way real boards are reported to:
// late replies, a deaf spell right after opening, lost replies, a second program on the
// same node whose replies reach every handle, and a combined MultiServoOff that is ignored.
// The servos and the protocol are the emulated xArm's; only the timing and the faults are
// this fake's. Driven by a Clock: on a SimClock waiting advances simulated time (SDK tests),
// on the steady clock it sleeps like a device would (the fake hidapi for CLI tests).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "devices/xarm_emulator/xarm_emulator.hpp"
#include "protocol/robot_commands/frame.hpp"

namespace armctl::testing {

struct FakeHidBehaviour {
  Duration reply_delay{0};      // every reply leaves this long after its request
  Duration deaf_after_open{0};  // requests written earlier than this after opening are lost
  Duration hold_after_open{0};  // no reply leaves earlier than this after opening
  std::set<int> drop_replies;   // replies lost on the way, counted 1, 2, ... from opening
  bool ignore_combined_servo_off = false;  // a MultiServoOff for more than one servo does nothing
  Duration other_opener_every{0};  // another program reads servo 1 this often (0 = none)
  std::string other_opener = "fake-poller (pid 4242)";  // how the seam names it
};

// Reads "reply_delay_ms=450,deaf_ms=1200,hold_ms=1200,drop=2+3,ignore_combined_off=1,
// other_every_ms=300"
// (every key optional). Throws ArmctlError(invalid_argument) naming a bad entry.
FakeHidBehaviour parse_fake_hid_behaviour(const std::string& text);

class FakeXarmHid {
 public:
  using Report = std::array<std::uint8_t, 64>;
  using WaitUntil = std::function<void(TimePoint)>;

  using Handle = std::size_t;

  // `clock` must outlive this.
  FakeXarmHid(const Clock& clock, FakeHidBehaviour behaviour);

  // A program opened the node. Like hidraw, every handle gets a copy of every reply from
  // then on. The first open starts the board's deaf/held spell.
  Handle open();
  // One output report (report ID first) at clock.now(), from any handle.
  void write(std::span<const std::uint8_t> report);
  // The next input report for `handle`, waiting with `wait_until` (advance a SimClock, or
  // sleep) until one is due or `deadline` passes.
  std::optional<Report> read(Handle handle, TimePoint deadline, const WaitUntil& wait_until);

  xarm::XarmServos& servos() { return emulator_.servos(); }
  const FakeHidBehaviour& behaviour() const { return behaviour_; }
  // Every frame the host wrote (also the ignored ones), in order.
  const std::vector<rc::Frame>& requests() const { return requests_; }
  int replies_dropped() const { return dropped_; }
  int ignored_requests() const { return ignored_; }
  int other_opener_requests() const { return other_requests_; }

 private:
  void handle(const rc::Frame& frame);
  void run_other_opener(TimePoint now);
  std::optional<TimePoint> next_due(Handle handle) const;
  using Queue = std::deque<std::pair<TimePoint, rc::Frame>>;

  const Clock& clock_;
  FakeHidBehaviour behaviour_;
  xarm::XarmEmulator emulator_;
  TimePoint opened_at_{};
  TimePoint next_other_{};
  std::vector<Queue> handles_;  // replies on their way to each open handle
  std::vector<rc::Frame> requests_;
  int replies_ = 0;
  int dropped_ = 0;
  int ignored_ = 0;
  int other_requests_ = 0;
};

}  // namespace armctl::testing

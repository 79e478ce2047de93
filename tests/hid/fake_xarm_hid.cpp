#include "fake_xarm_hid.hpp"

#include <charconv>

#include "core/error.hpp"
#include "protocol/robot_commands/command_codes.hpp"
#include "protocol/robot_commands/hid_report.hpp"

namespace armctl::testing {
namespace {

int to_int(const std::string& key, const std::string& value) {
  int v = 0;
  auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (ec != std::errc{} || end != value.data() + value.size() || v < 0) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "fake HID: " + key + "=" + value + " is not a number >= 0");
  }
  return v;
}

}  // namespace

FakeHidBehaviour parse_fake_hid_behaviour(const std::string& text) {
  FakeHidBehaviour b;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find(',', pos);
    if (end == std::string::npos) end = text.size();
    const std::string entry = text.substr(pos, end - pos);
    pos = end + 1;
    if (entry.empty()) continue;
    const auto eq = entry.find('=');
    const std::string key = entry.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : entry.substr(eq + 1);
    if (key == "reply_delay_ms") b.reply_delay = std::chrono::milliseconds(to_int(key, value));
    else if (key == "deaf_ms") b.deaf_after_open = std::chrono::milliseconds(to_int(key, value));
    else if (key == "hold_ms") b.hold_after_open = std::chrono::milliseconds(to_int(key, value));
    else if (key == "other_every_ms")
      b.other_opener_every = std::chrono::milliseconds(to_int(key, value));
    else if (key == "ignore_combined_off") b.ignore_combined_servo_off = to_int(key, value) != 0;
    else if (key == "drop") {
      std::size_t p = 0;
      while (p <= value.size()) {
        std::size_t e = value.find('+', p);
        if (e == std::string::npos) e = value.size();
        b.drop_replies.insert(to_int(key, value.substr(p, e - p)));
        p = e + 1;
      }
    } else {
      throw ArmctlError(ErrorKind::invalid_argument,
                        "fake HID: unknown entry \"" + entry +
                            "\" (allowed: reply_delay_ms, deaf_ms, hold_ms, drop, ignore_combined_off, "
                            "other_every_ms)");
    }
  }
  return b;
}

FakeXarmHid::FakeXarmHid(const Clock& clock, FakeHidBehaviour behaviour)
    : clock_(clock),
      behaviour_(std::move(behaviour)),
      emulator_(clock, xarm::XarmEmulatorOptions{}, [this](const rc::Frame& f) {
        // Every reply the board sends, numbered from opening; some are lost on the way.
        ++replies_;
        if (behaviour_.drop_replies.count(replies_)) {
          ++dropped_;
          return;
        }
        const TimePoint at =
            std::max(clock_.now() + behaviour_.reply_delay, opened_at_ + behaviour_.hold_after_open);
        for (auto& queue : handles_) {
          auto it = queue.begin();
          while (it != queue.end() && it->first <= at) ++it;
          queue.insert(it, {at, f});
        }
      }) {}

FakeXarmHid::Handle FakeXarmHid::open() {
  if (handles_.empty()) {
    opened_at_ = clock_.now();
    next_other_ = opened_at_ + behaviour_.other_opener_every;
  }
  handles_.emplace_back();
  return handles_.size() - 1;
}

void FakeXarmHid::write(std::span<const std::uint8_t> report) {
  auto frame = rc::decode_hid_report(report);
  if (!frame) return;  // a real board ignores what it cannot read
  requests_.push_back(*frame);
  run_other_opener(clock_.now());
  if (clock_.now() - opened_at_ < behaviour_.deaf_after_open) {
    ++ignored_;
    return;
  }
  if (behaviour_.ignore_combined_servo_off &&
      frame->cmd == static_cast<std::uint8_t>(rc::Command::MultiServoOff) &&
      !frame->data.empty() && frame->data[0] > 1) {
    ++ignored_;
    return;
  }
  handle(*frame);
}

void FakeXarmHid::handle(const rc::Frame& frame) {
  emulator_.poll();
  emulator_.board().handle(frame);
}

// The other program's requests; the board answers them on every handle, ours included.
void FakeXarmHid::run_other_opener(TimePoint now) {
  if (behaviour_.other_opener_every <= Duration::zero()) return;
  while (next_other_ <= now) {
    ++other_requests_;
    rc::Frame read;
    read.cmd = static_cast<std::uint8_t>(rc::Command::ServoPositionRead);
    read.data = {1, 1};
    handle(read);
    next_other_ += behaviour_.other_opener_every;
  }
}

std::optional<TimePoint> FakeXarmHid::next_due(Handle handle) const {
  std::optional<TimePoint> t;
  const Queue& pending = handles_.at(handle);
  if (!pending.empty()) t = pending.front().first;
  if (behaviour_.other_opener_every > Duration::zero() && (!t || next_other_ < *t)) {
    t = next_other_;
  }
  return t;
}

std::optional<FakeXarmHid::Report> FakeXarmHid::read(Handle handle, TimePoint deadline,
                                                     const WaitUntil& wait_until) {
  for (;;) {
    run_other_opener(clock_.now());
    Queue& pending = handles_.at(handle);
    if (!pending.empty() && pending.front().first <= clock_.now()) {
      Report r{};
      const auto bytes = rc::encode_frame(pending.front().second);
      std::copy(bytes.begin(), bytes.end(), r.begin());
      pending.pop_front();
      return r;
    }
    if (clock_.now() >= deadline) return std::nullopt;
    const auto due = next_due(handle);
    wait_until(due && *due < deadline ? *due : deadline);
  }
}

}  // namespace armctl::testing

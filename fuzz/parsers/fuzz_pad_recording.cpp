// Gamepad recordings (jog/gamepad_replay.hpp, docs/gamepad.md "Recordings") on hostile
// input: never a crash; every error is invalid_config naming the source; anything accepted
// has a named pad with the left stick's axes, times in order and in range, EV_ABS events
// only on declared axes, button values 0..2; it survives a format/parse round trip; and its
// replay hands over every event exactly once, in order, whatever the poll times.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include <linux/input-event-codes.h>

#include "jog/gamepad_replay.hpp"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_pad_recording: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl::jog;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto r = parse_pad_recording(text, "fuzz");
  if (!r) {
    check(r.error().message.rfind("fuzz:", 0) == 0, "an error that does not name the file");
    check(r.error().kind == armctl::ErrorKind::invalid_config, "an error of another kind");
    return 0;
  }
  check(!r->pad.name.empty(), "a pad without a name");
  check(r->pad.axes.contains(ABS_X) && r->pad.axes.contains(ABS_Y), "a pad without the left stick");
  for (const auto& [code, a] : r->pad.axes) check(a.minimum < a.maximum, "an axis without a range");
  std::size_t events = 0;
  double last = 0;
  for (const auto& l : r->lines) {
    check(std::isfinite(l.time) && l.time >= last && l.time <= kPadRecordingMaxTime, "times out of order or range");
    last = l.time;
    if (l.kind != PadRecordingLine::Kind::event) continue;
    ++events;
    if (l.type == EV_ABS) check(r->pad.axes.contains(l.code), "an event on an undeclared axis");
    if (l.type == EV_KEY) check(l.value >= 0 && l.value <= 2, "a button value outside 0..2");
  }
  // Written back (as the recorder writes), it reads back the same.
  auto again = parse_pad_recording(format_pad_recording(*r), "again");
  check(again.ok(), "the formatted recording does not parse");
  check(again->pad.name == r->pad.name && again->lines.size() == r->lines.size(), "the round trip changed the recording");
  for (std::size_t i = 0; i < r->lines.size(); ++i) {
    const auto &a = r->lines[i], &b = again->lines[i];
    check(a.kind == b.kind && a.type == b.type && a.code == b.code && a.value == b.value &&
              std::abs(a.time - b.time) <= 1e-6,
          "the round trip changed a line");
  }
  // Polled at uneven times (a step from the input's length), then at the end: every event
  // comes once, in order, and the replay ends. A loss or a return ends a poll, so the end
  // takes at most one poll per line.
  GamepadReplay replay(*r, "fuzz");
  const auto step = std::chrono::milliseconds(1 + size % 997);
  armctl::TimePoint now{}, previous{};
  std::size_t seen = 0;
  bool ended = false;
  auto take = [&](armctl::TimePoint at) {
    const PadPoll p = replay.poll(at);
    for (const auto& e : p.events) {
      check(e.time >= previous && e.time <= at, "an event out of order or early");
      previous = e.time;
    }
    seen += p.events.size();
    ended = p.ended;
  };
  for (int polls = 0; polls < 1000 && !ended; ++polls, now += step) take(now);
  const auto end = armctl::TimePoint{} + std::chrono::duration_cast<armctl::Duration>(
                                             std::chrono::duration<double>(last + 1));
  for (std::size_t k = 0; k <= r->lines.size() && !ended; ++k) take(std::max(now, end));
  check(ended && seen == events, "events lost or repeated, or no end");
  return 0;
}

// A gamepad's events recorded as text and replayed (docs/gamepad.md "Recordings"): what
// tests and demos drive `armctl jog --gamepad-replay` with, on a machine without a pad or
// uinput. The format, one item a line ('#' comments, blank lines skipped):
//
//   device Microsoft X-Box 360 pad      the pad's name (once, first)
//   axis ABS_X -32768 32767             an absolute axis and its range (before the events;
//                                       ABS_X and ABS_Y at least)
//   0.250 EV_KEY BTN_TL 1               an event: time in s from the start (never before the
//                                       line above), type, code, value (names as the kernel's
//                                       input-event-codes.h spells them, or numbers)
//   2.000 unplugged                     the pad lost (then `plugged`: the same pad back)
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "jog/gamepad_source.hpp"

namespace armctl::jog {

struct PadRecordingLine {
  enum class Kind { event, unplugged, plugged };
  Kind kind = Kind::event;
  double time = 0;  // s from the start
  std::uint16_t type = 0, code = 0;
  std::int32_t value = 0;
};

struct PadRecording {
  PadDescription pad;
  std::vector<PadRecordingLine> lines;
};

// At most this long (s) and this many lines: far beyond any demo, and a bound on memory.
inline constexpr double kPadRecordingMaxTime = 86400;
inline constexpr std::size_t kPadRecordingMaxLines = 1'000'000;

// Errors (invalid_config): "source:line:column: found ...; expected ..." naming what is
// allowed there.
Result<PadRecording> parse_pad_recording(std::string_view text, std::string_view source);
Result<PadRecording> read_pad_recording(const std::filesystem::path& path);
// The text parse_pad_recording reads back as `recording` (times to the microsecond, the
// kernel's names for types and codes).
std::string format_pad_recording(const PadRecording& recording);

// Plays a recording on the session's clock: the first poll is time 0, and each poll hands
// over every line whose time has come. Ends after the last line.
class GamepadReplay final : public GamepadSource {
 public:
  GamepadReplay(PadRecording recording, std::string description);
  PadPoll poll(TimePoint now) override;
  std::string description() const override { return description_; }

 private:
  PadRecording recording_;
  std::string description_;
  std::optional<TimePoint> start_;
  std::size_t next_ = 0;
};

}  // namespace armctl::jog

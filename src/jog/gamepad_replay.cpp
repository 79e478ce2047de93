#include "jog/gamepad_replay.hpp"

#include <libevdev/libevdev.h>
#include <linux/input-event-codes.h>

#include <charconv>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/printable.hpp"
#include "core/regular_file.hpp"
#include "files/line_reader.hpp"

namespace armctl::jog {
namespace {

using files::TextField;
using files::TextLine;

constexpr std::uintmax_t kMaxBytes = 64u << 20;

template <typename T>
std::optional<T> integer(std::string_view s) {
  T v{};
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<double> seconds(std::string_view s) {
  double v = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// An event type by its name (EV_KEY) or number, one the kernel defines.
std::optional<std::uint16_t> event_type(std::string_view s) {
  int t = libevdev_event_type_from_name_n(s.data(), s.size());
  if (t < 0) t = integer<int>(s).value_or(-1);
  if (t < 0 || t > EV_MAX || libevdev_event_type_get_max(unsigned(t)) < 0) return std::nullopt;
  return std::uint16_t(t);
}

// A code of `type` by its name (ABS_X, BTN_TL) or number up to the type's largest.
std::optional<std::uint16_t> event_code(std::uint16_t type, std::string_view s) {
  int c = libevdev_event_code_from_name_n(type, s.data(), s.size());
  if (c < 0) c = integer<int>(s).value_or(-1);
  if (c < 0 || c > libevdev_event_type_get_max(type)) return std::nullopt;
  return std::uint16_t(c);
}

std::string code_name(std::uint16_t type, std::uint16_t code) {
  const char* name = libevdev_event_code_get_name(type, code);
  return name ? name : std::to_string(code);
}

class Parser {
 public:
  explicit Parser(std::string_view source) : source_(source) {}

  Result<PadRecording> parse(std::string_view text) {
    const auto last = files::read_lines(text, [&](const TextLine& line) { return take(line); });
    if (!last) return last.error();
    if (!device_seen_) return fail(*last, 1, "the end of the file", "a line 'device NAME' naming the pad");
    for (std::uint16_t code : {ABS_X, ABS_Y})
      if (!r_.pad.axes.contains(code))
        return fail(*last, 1, fmt::format("no line 'axis {} ...'", code_name(EV_ABS, code)),
                    "the left stick's axes ABS_X and ABS_Y with their ranges: a gamepad has them");
    return std::move(r_);
  }

 private:
  Error fail(std::size_t line, std::size_t column, const std::string& found, const std::string& expected) const {
    return files::file_error(source_, line, column, fmt::format("found {}; expected {}", found, expected));
  }
  static std::string quoted(const TextField& f) { return "'" + files::shown(f.text) + "'"; }

  Status take(const TextLine& line) {
    const auto& f = line.fields;
    const std::size_t n = line.number;
    if (r_.lines.size() >= kPadRecordingMaxLines)
      return fail(n, 1, "more lines", fmt::format("at most {} event lines", kPadRecordingMaxLines));
    if (f[0].text == "device") {
      if (device_seen_) return fail(n, 1, "a second 'device' line", "one 'device NAME' line, first");
      std::string_view name = line.code.substr(f[0].column - 1 + f[0].text.size());
      while (!name.empty() && files::is_blank(name.front())) name.remove_prefix(1);
      while (!name.empty() && files::is_blank(name.back())) name.remove_suffix(1);
      if (name.empty()) return fail(n, f[0].column + f[0].text.size(), "the end of the line", "the pad's name");
      r_.pad.name = printable(name);
      device_seen_ = true;
      return Ok{};
    }
    if (!device_seen_) return fail(n, f[0].column, quoted(f[0]), "'device NAME' as the first line");
    if (f[0].text == "axis") return axis(n, f);
    return event(n, f);
  }

  Status axis(std::size_t n, const std::vector<TextField>& f) {
    if (!r_.lines.empty()) return fail(n, f[0].column, "an 'axis' line after events", "every axis before the first event");
    if (f.size() != 4) return fail(n, f[0].column, fmt::format("{} values after 'axis'", f.size() - 1), "'axis CODE MIN MAX'");
    const auto code = event_code(EV_ABS, f[1].text);
    if (!code) return fail(n, f[1].column, quoted(f[1]), "an absolute axis: a name such as ABS_X, or 0..63");
    if (r_.pad.axes.contains(*code)) return fail(n, f[1].column, quoted(f[1]) + " again", "each axis once");
    const auto lo = integer<std::int32_t>(f[2].text), hi = integer<std::int32_t>(f[3].text);
    if (!lo) return fail(n, f[2].column, quoted(f[2]), "the axis's minimum, a whole number");
    if (!hi || *hi <= *lo) return fail(n, f[3].column, quoted(f[3]), "the axis's maximum, a whole number above its minimum");
    r_.pad.axes[*code] = PadAxis{*lo, *hi, std::nullopt};
    return Ok{};
  }

  Status event(std::size_t n, const std::vector<TextField>& f) {
    const auto t = seconds(f[0].text);
    if (!t || *t < 0 || *t > kPadRecordingMaxTime)
      return fail(n, f[0].column, quoted(f[0]),
                  fmt::format("'device', 'axis', or a time in s (0..{:g}) starting an event line", kPadRecordingMaxTime));
    if (*t < time_)
      return fail(n, f[0].column, quoted(f[0]), fmt::format("a time not before the line above's ({:g} s)", time_));
    time_ = *t;
    PadRecordingLine l;
    l.time = *t;
    if (f.size() == 2 && (f[1].text == "unplugged" || f[1].text == "plugged")) {
      const bool unplug = f[1].text == "unplugged";
      if (unplug == unplugged_)
        return fail(n, f[1].column, quoted(f[1]), unplug ? "'plugged' first: the pad is unplugged" : "'unplugged' first: the pad is plugged in");
      unplugged_ = unplug;
      l.kind = unplug ? PadRecordingLine::Kind::unplugged : PadRecordingLine::Kind::plugged;
      r_.lines.push_back(l);
      return Ok{};
    }
    if (f.size() != 4)
      return fail(n, f[0].column, fmt::format("{} values after the time", f.size() - 1),
                  "'TIME TYPE CODE VALUE' or 'TIME unplugged' or 'TIME plugged'");
    if (unplugged_) return fail(n, f[1].column, "an event while the pad is unplugged", "'plugged' first");
    const auto type = event_type(f[1].text);
    if (!type) return fail(n, f[1].column, quoted(f[1]), "an event type: EV_SYN, EV_KEY, EV_ABS, EV_MSC ... or its number");
    const auto code = event_code(*type, f[2].text);
    if (!code)
      return fail(n, f[2].column, quoted(f[2]),
                  fmt::format("a code of that type (such as {}) or 0..{}", code_name(*type, 0),
                              libevdev_event_type_get_max(*type)));
    const auto value = integer<std::int32_t>(f[3].text);
    if (!value) return fail(n, f[3].column, quoted(f[3]), "a whole number value");
    if (*type == EV_ABS && !r_.pad.axes.contains(*code))
      return fail(n, f[2].column, quoted(f[2]),
                  fmt::format("an axis with a line 'axis {} MIN MAX' above", code_name(EV_ABS, *code)));
    if (*type == EV_KEY && (*value < 0 || *value > 2))
      return fail(n, f[3].column, quoted(f[3]), "0 (released), 1 (pressed) or 2 (repeated) for a button");
    l.type = *type;
    l.code = *code;
    l.value = *value;
    r_.lines.push_back(l);
    return Ok{};
  }

  std::string source_;
  PadRecording r_;
  bool device_seen_ = false, unplugged_ = false;
  double time_ = 0;
};

}  // namespace

Result<PadRecording> parse_pad_recording(std::string_view text, std::string_view source) {
  return Parser(source).parse(text);
}

Result<PadRecording> read_pad_recording(const std::filesystem::path& path) {
  auto text = read_text_file(path, "gamepad recording", kMaxBytes);
  if (!text) return text.error();
  return parse_pad_recording(*text, path.string());
}

std::string format_pad_recording(const PadRecording& recording) {
  std::string out = "# armctl gamepad recording: time in s, type, code, value (docs/gamepad.md)\n";
  // '#' would start a comment, and a name is needed: the name as close as the format allows.
  std::string name = recording.pad.name;
  for (char& c : name)
    if (c == '#' || c == '\n' || c == '\r') c = '_';
  if (name.find_first_not_of(" \t") == std::string::npos) name = "unnamed pad";
  out += "device " + name + "\n";
  for (const auto& [code, a] : recording.pad.axes)
    out += fmt::format("axis {} {} {}\n", code_name(EV_ABS, code), a.minimum, a.maximum);
  for (const PadRecordingLine& l : recording.lines) {
    if (l.kind == PadRecordingLine::Kind::event) {
      const char* type = libevdev_event_type_get_name(l.type);
      out += fmt::format("{:.6f} {} {} {}\n", l.time, type ? type : std::to_string(l.type), code_name(l.type, l.code),
                         l.value);
    } else {
      out += fmt::format("{:.6f} {}\n", l.time, l.kind == PadRecordingLine::Kind::unplugged ? "unplugged" : "plugged");
    }
  }
  return out;
}

GamepadReplay::GamepadReplay(PadRecording recording, std::string description)
    : recording_(std::move(recording)), description_(std::move(description)) {}

PadPoll GamepadReplay::poll(TimePoint now) {
  PadPoll p;
  if (!start_) {
    start_ = now;
    p.connected = recording_.pad;
  }
  const double elapsed = std::chrono::duration<double>(now - *start_).count();
  for (; next_ < recording_.lines.size() && recording_.lines[next_].time <= elapsed; ++next_) {
    const PadRecordingLine& l = recording_.lines[next_];
    if (l.kind == PadRecordingLine::Kind::unplugged) {
      // What follows waits for the next poll: the loss comes after the events before it.
      p.unplugged = true;
      ++next_;
      return p;
    }
    if (l.kind == PadRecordingLine::Kind::plugged) {
      if (!p.events.empty() || p.connected) return p;  // plugged in afresh at the next poll
      p.connected = recording_.pad;
      continue;
    }
    const auto at = *start_ + std::chrono::duration_cast<Duration>(std::chrono::duration<double>(l.time));
    p.events.push_back(PadEvent{l.type, l.code, l.value, at});
  }
  p.ended = next_ == recording_.lines.size();
  return p;
}

}  // namespace armctl::jog

#include "files/recording_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include <fmt/core.h>

#include "core/atomic_file.hpp"
#include "core/units.hpp"
#include "core/regular_file.hpp"
#include "files/line_reader.hpp"

namespace armctl::files {

using motion::Recording;
using motion::RecordingSample;

namespace {

constexpr std::uintmax_t kRecordingMaxBytes = 64u << 20;
constexpr std::size_t kJointNameMax = 64;
constexpr double kMaxTime = 1e6;  // s: 11 days, far beyond any recording
constexpr double kMaxSi = 1e3;  // rad or m: far beyond any joint, and finite in every unit

std::optional<double> number(std::string_view s) {
  double v = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

bool good_name(std::string_view s) {
  if (s.empty() || s.size() > kJointNameMax) return false;
  if (!(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

class Parser {
 public:
  explicit Parser(std::string_view source) : source_(source) {}

  Result<Recording> parse(std::string_view text) {
    const auto last = read_lines(text, [&](const TextLine& line) { return take(line.number, line.fields); });
    if (!last) return last.error();
    const std::size_t line_no = *last;
    if (stage_ != Stage::samples)
      return fail(line_no, 1, "the end of the file", std::string("'") + kStageWord[int(stage_)] + " ...' (a header line)");
    if (r_.samples.empty()) return fail(line_no, 1, "no samples", "at least one sample line after the header");
    return std::move(r_);
  }

 private:
  enum class Stage { arm, rate, joints, samples };
  static constexpr const char* kStageWord[] = {"arm", "rate", "joints", ""};

  Error fail(std::size_t line, std::size_t column, const std::string& found, const std::string& expected) const {
    return file_error(source_, line, column, fmt::format("found {}; expected {}", found, expected));
  }
  static std::string in_quotes(const TextField& t) { return "'" + files::shown(t.text, 40) + "'"; }

  Status header(std::size_t line, const std::vector<TextField>& t, std::size_t args_min, std::size_t args_max) {
    const char* word = kStageWord[int(stage_)];
    if (t[0].text != word)
      return fail(line, t[0].column, in_quotes(t[0]), fmt::format("the header line '{} ...'", word));
    if (t.size() - 1 < args_min)
      return fail(line, t[0].column + t[0].text.size(), "the end of the line", fmt::format("a value after '{}'", word));
    if (t.size() - 1 > args_max)
      return fail(line, t[args_max + 1].column, in_quotes(t[args_max + 1]), "the end of the line");
    return Ok{};
  }

  Status take(std::size_t line, const std::vector<TextField>& t) {
    switch (stage_) {
      case Stage::arm: {
        if (auto s = header(line, t, 1, 1); !s) return s;
        if (!good_name(t[1].text)) return fail(line, t[1].column, in_quotes(t[1]), "an arm name (letters, digits, '_', '-')");
        r_.arm = std::string(t[1].text);
        stage_ = Stage::rate;
        return Ok{};
      }
      case Stage::rate: {
        if (auto s = header(line, t, 1, 1); !s) return s;
        auto rate = parse_rate(t[1].text);
        if (!rate) return fail(line, t[1].column, in_quotes(t[1]), "a rate of 1..1000 Hz such as '20Hz'");
        r_.rate = *rate;
        stage_ = Stage::joints;
        return Ok{};
      }
      case Stage::joints: {
        if (auto s = header(line, t, 1, kRecordingMaxJoints); !s) return s;
        for (std::size_t i = 1; i < t.size(); ++i) {
          const auto colon = t[i].text.find(':');
          const std::string_view name = t[i].text.substr(0, colon);
          const std::string_view unit = colon == std::string_view::npos ? "" : t[i].text.substr(colon + 1);
          if (!good_name(name)) return fail(line, t[i].column, in_quotes(t[i]), "a joint name then ':' and its unit (base:deg)");
          const QuantityUnit* u = unit.empty() ? nullptr : find_unit(unit);
          if (u == nullptr)
            return fail(line, t[i].column + name.size() + (colon == std::string_view::npos ? 0 : 1),
                        unit.empty() ? "no unit" : "unit '" + files::shown(unit, 40) + "'",
                        "':deg', ':rad' (angles), ':mm' or ':m' (lengths) after the joint name");
          for (const auto& j : r_.joints)
            if (j.name == name) return fail(line, t[i].column, in_quotes(t[i]), "each joint named once");
          r_.joints.push_back({std::string(name), u->dimension});
          units_.push_back(u);
        }
        stage_ = Stage::samples;
        return Ok{};
      }
      case Stage::samples: {
        if (r_.samples.size() == kRecordingMaxSamples)
          return fail(line, 1, "more samples", fmt::format("at most {} samples", kRecordingMaxSamples));
        RecordingSample s;
        auto time = number(t[0].text);
        if (!time || *time < 0 || *time > kMaxTime)
          return fail(line, t[0].column, in_quotes(t[0]), fmt::format("a time in s, 0..{:g}", kMaxTime));
        if (!r_.samples.empty() && !(*time > r_.samples.back().time))
          return fail(line, t[0].column, in_quotes(t[0]),
                      fmt::format("a time after the previous sample's {}", r_.samples.back().time));
        s.time = *time;
        const std::size_t n = r_.joints.size();
        if (t.size() - 1 < n)
          return fail(line, t.back().column + t.back().text.size(), "the end of the line",
                      fmt::format("{} joint values after the time (one per joint), found {}", n, t.size() - 1));
        if (t.size() - 1 > n) return fail(line, t[n + 1].column, in_quotes(t[n + 1]), "the end of the line");
        for (std::size_t i = 0; i < n; ++i) {
          auto v = number(t[i + 1].text);
          if (!v || std::abs(*v * units_[i]->to_si) > kMaxSi)
            return fail(line, t[i + 1].column, in_quotes(t[i + 1]),
                        fmt::format("a number (joint {} in {})", r_.joints[i].name, units_[i]->name));
          s.positions.push_back(*v * units_[i]->to_si);
        }
        r_.samples.push_back(std::move(s));
        return Ok{};
      }
    }
    return Ok{};
  }

  std::string_view source_;
  Stage stage_ = Stage::arm;
  Recording r_;
  std::vector<const QuantityUnit*> units_;  // what each joint's values are written in
};

// Shortest text that reads back as `v`.
std::string shortest(double v) {
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : fmt::format("{}", v);
}

}  // namespace

Result<Recording> parse_recording(std::string_view text, std::string_view source) {
  return Parser(source).parse(text);
}

Result<Recording> read_recording(const std::filesystem::path& path) {
  auto text = read_text_file(path, "recording", kRecordingMaxBytes);
  if (!text) return text.error();
  return parse_recording(*text, path.string());
}

std::string format_recording(const Recording& r) {
  std::string out = "# armctl recording: time in s, then one value per joint (docs/teach.md)\n";
  out += "arm " + r.arm + "\n";
  out += "rate " + shortest(r.rate) + "Hz\n";
  out += "joints";
  for (const auto& j : r.joints) out += " " + j.name + ":" + std::string(display_unit_of(j.dimension).name);
  out += "\n";
  for (const auto& s : r.samples) {
    out += shortest(s.time);
    // Not to_display: that shows a value under 5e-7 as 0, and a file must read back as written.
    // (+ 0.0 turns -0 into 0.)
    for (std::size_t i = 0; i < s.positions.size() && i < r.joints.size(); ++i)
      out += " " + shortest(s.positions[i] / display_unit_of(r.joints[i].dimension).to_si + 0.0);
    out += "\n";
  }
  return out;
}

Status write_recording(const std::filesystem::path& path, const Recording& recording) {
  const std::string text = format_recording(recording);
  return write_file_atomically(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

Result<double> parse_rate(std::string_view text) {
  std::string_view digits = text;
  if (digits.size() >= 2 && digits.substr(digits.size() - 2) == "Hz") digits.remove_suffix(2);
  while (!digits.empty() && digits.back() == ' ') digits.remove_suffix(1);
  auto v = number(digits);
  if (!v || *v < 1 || *v > kRecordingMaxRate)
    return Error{ErrorKind::invalid_argument,
                 fmt::format("rate '{}': allowed is 1..{:g} Hz, such as '20Hz'", shown(text, 40), kRecordingMaxRate)};
  return *v;
}

}  // namespace armctl::files

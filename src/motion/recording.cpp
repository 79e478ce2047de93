#include "motion/recording.hpp"

#include "core/source_place.hpp"
#include "core/atomic_file.hpp"
#include "core/regular_file.hpp"


#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>
#include <optional>

#include <fmt/core.h>

namespace armctl::motion {

namespace {

constexpr std::uintmax_t kRecordingMaxBytes = 64u << 20;
constexpr std::size_t kJointNameMax = 64;
constexpr double kMaxTime = 1e6;  // s: 11 days, far beyond any recording
constexpr double kMaxSi = 1e3;  // rad or m: far beyond any joint, and finite in every unit

struct Token {
  std::string_view text;
  std::size_t column = 0;  // 1-based
};

// Splits a line (comment removed) into tokens with their columns.
std::vector<Token> tokens_of(std::string_view line) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    out.push_back({line.substr(start, i - start), start + 1});
  }
  return out;
}

// Text safe to quote in a message: control and non-ASCII bytes as \xNN, at most 40 chars.
std::string printable(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size() && i < 40; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    out += (c >= 0x20 && c < 0x7f) ? std::string(1, char(c)) : fmt::format("\\x{:02x}", c);
  }
  if (s.size() > 40) out += "...";
  return out;
}

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

struct Unit {
  std::string_view name;
  Dimension dimension;
  double to_si;
};
constexpr Unit kUnits[] = {{"deg", Dimension::angle, M_PI / 180},
                           {"rad", Dimension::angle, 1},
                           {"mm", Dimension::length, 1e-3},
                           {"m", Dimension::length, 1}};

// The unit a recording is written in: deg for angles, mm for lengths.
const Unit& unit_of(Dimension d) { return d == Dimension::angle ? kUnits[0] : kUnits[2]; }

class Parser {
 public:
  explicit Parser(std::string_view source) : source_(source) {}

  Result<Recording> parse(std::string_view text) {
    std::size_t pos = 0;
    std::size_t line_no = 0;
    while (pos <= text.size()) {
      const std::size_t end = std::min(text.find('\n', pos), text.size());
      ++line_no;
      std::string_view line = text.substr(pos, end - pos);
      if (auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
      const auto tokens = tokens_of(line);
      if (!tokens.empty())
        if (auto s = take(line_no, tokens); !s) return s.error();
      if (end == text.size()) break;
      pos = end + 1;
    }
    if (stage_ != Stage::samples)
      return fail(line_no, 1, "the end of the file", std::string("'") + kStageWord[int(stage_)] + " ...' (a header line)");
    if (r_.samples.empty()) return fail(line_no, 1, "no samples", "at least one sample line after the header");
    return std::move(r_);
  }

 private:
  enum class Stage { arm, rate, joints, samples };
  static constexpr const char* kStageWord[] = {"arm", "rate", "joints", ""};

  Error fail(std::size_t line, std::size_t column, const std::string& found, const std::string& expected) const {
    return source_error(ErrorKind::invalid_config,
                        {std::string(source_), line, column, fmt::format("found {}; expected {}", found, expected)});
  }
  static std::string quoted(const Token& t) { return "'" + printable(t.text) + "'"; }

  Status header(std::size_t line, const std::vector<Token>& t, std::size_t args_min, std::size_t args_max) {
    const char* word = kStageWord[int(stage_)];
    if (t[0].text != word)
      return fail(line, t[0].column, quoted(t[0]), fmt::format("the header line '{} ...'", word));
    if (t.size() - 1 < args_min)
      return fail(line, t[0].column + t[0].text.size(), "the end of the line", fmt::format("a value after '{}'", word));
    if (t.size() - 1 > args_max)
      return fail(line, t[args_max + 1].column, quoted(t[args_max + 1]), "the end of the line");
    return Ok{};
  }

  Status take(std::size_t line, const std::vector<Token>& t) {
    switch (stage_) {
      case Stage::arm: {
        if (auto s = header(line, t, 1, 1); !s) return s;
        if (!good_name(t[1].text)) return fail(line, t[1].column, quoted(t[1]), "an arm name (letters, digits, '_', '-')");
        r_.arm = std::string(t[1].text);
        stage_ = Stage::rate;
        return Ok{};
      }
      case Stage::rate: {
        if (auto s = header(line, t, 1, 1); !s) return s;
        auto rate = parse_rate(t[1].text);
        if (!rate) return fail(line, t[1].column, quoted(t[1]), "a rate of 1..1000 Hz such as '20Hz'");
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
          if (!good_name(name)) return fail(line, t[i].column, quoted(t[i]), "a joint name then ':' and its unit (base:deg)");
          const Unit* u = nullptr;
          for (const Unit& k : kUnits)
            if (k.name == unit) u = &k;
          if (u == nullptr)
            return fail(line, t[i].column + name.size() + (colon == std::string_view::npos ? 0 : 1),
                        unit.empty() ? "no unit" : "unit '" + printable(unit) + "'",
                        "':deg', ':rad' (angles), ':mm' or ':m' (lengths) after the joint name");
          for (const auto& j : r_.joints)
            if (j.name == name) return fail(line, t[i].column, quoted(t[i]), "each joint named once");
          r_.joints.push_back({std::string(name), u->dimension});
          to_si_.push_back(u->to_si);
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
          return fail(line, t[0].column, quoted(t[0]), fmt::format("a time in s, 0..{:g}", kMaxTime));
        if (!r_.samples.empty() && !(*time > r_.samples.back().time))
          return fail(line, t[0].column, quoted(t[0]),
                      fmt::format("a time after the previous sample's {}", r_.samples.back().time));
        s.time = *time;
        const std::size_t n = r_.joints.size();
        if (t.size() - 1 < n)
          return fail(line, t.back().column + t.back().text.size(), "the end of the line",
                      fmt::format("{} joint values after the time (one per joint), found {}", n, t.size() - 1));
        if (t.size() - 1 > n) return fail(line, t[n + 1].column, quoted(t[n + 1]), "the end of the line");
        for (std::size_t i = 0; i < n; ++i) {
          auto v = number(t[i + 1].text);
          if (!v || std::abs(*v * to_si_[i]) > kMaxSi)
            return fail(line, t[i + 1].column, quoted(t[i + 1]),
                        fmt::format("a number (joint {} in {})", r_.joints[i].name, unit_name(i)));
          s.positions.push_back(*v * to_si_[i]);
        }
        r_.samples.push_back(std::move(s));
        return Ok{};
      }
    }
    return Ok{};
  }

  std::string_view unit_name(std::size_t i) const {
    for (const Unit& k : kUnits)
      if (k.to_si == to_si_[i] && k.dimension == r_.joints[i].dimension) return k.name;
    return "?";
  }

  std::string_view source_;
  Stage stage_ = Stage::arm;
  Recording r_;
  std::vector<double> to_si_;
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
  for (const auto& j : r.joints) out += " " + j.name + ":" + std::string(unit_of(j.dimension).name);
  out += "\n";
  for (const auto& s : r.samples) {
    out += shortest(s.time);
    // Not to_display: that shows a value under 5e-7 as 0, and a file must read back as written.
    // (+ 0.0 turns -0 into 0.)
    for (std::size_t i = 0; i < s.positions.size() && i < r.joints.size(); ++i)
      out += " " + shortest(s.positions[i] / unit_of(r.joints[i].dimension).to_si + 0.0);
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
                 fmt::format("rate '{}': allowed is 1..{:g} Hz, such as '20Hz'", printable(text), kRecordingMaxRate)};
  return *v;
}

std::vector<RecordingSample> smooth(const std::vector<RecordingSample>& samples, std::size_t half_window) {
  std::vector<RecordingSample> out = samples;
  if (samples.size() < 3 || half_window == 0) return out;
  for (std::size_t i = 1; i + 1 < samples.size(); ++i) {
    // A window symmetric around i, narrowed at the ends so that it stays centred (no lag).
    const std::size_t h = std::min({half_window, i, samples.size() - 1 - i});
    for (std::size_t j = 0; j < out[i].positions.size(); ++j) {
      double sum = 0;
      for (std::size_t k = i - h; k <= i + h; ++k) sum += samples[k].positions[j];
      out[i].positions[j] = sum / double(2 * h + 1);
    }
  }
  return out;
}

std::vector<std::size_t> keep_samples(const std::vector<RecordingSample>& samples,
                                      const std::vector<double>& tolerance) {
  if (samples.empty()) return {};
  if (samples.size() == 1) return {0};
  std::vector<bool> keep(samples.size(), false);
  keep.front() = keep.back() = true;
  // An explicit stack: recordings of 200,000 samples must not recurse that deep.
  std::vector<std::pair<std::size_t, std::size_t>> todo{{0, samples.size() - 1}};
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    if (b <= a + 1) continue;
    const double ta = samples[a].time, tb = samples[b].time;
    double worst = 1;  // in tolerances: above 1 the sample must be kept
    std::size_t worst_i = 0;
    for (std::size_t i = a + 1; i < b; ++i) {
      const double f = (samples[i].time - ta) / (tb - ta);
      for (std::size_t j = 0; j < samples[i].positions.size() && j < tolerance.size(); ++j) {
        const double line = samples[a].positions[j] + f * (samples[b].positions[j] - samples[a].positions[j]);
        const double e = std::abs(samples[i].positions[j] - line) / tolerance[j];
        if (e > worst) {
          worst = e;
          worst_i = i;
        }
      }
    }
    if (worst_i != 0) {
      keep[worst_i] = true;
      todo.push_back({a, worst_i});
      todo.push_back({worst_i, b});
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) out.push_back(i);
  return out;
}

}  // namespace armctl::motion

#include "files/path_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <span>
#include <string>

#include <fmt/core.h>

#include "core/ascii.hpp"
#include "core/json_reader.hpp"
#include "core/printable.hpp"
#include "files/line_reader.hpp"
#include "motion/move_limits.hpp"

namespace armctl::files {

namespace {

using Field = TextField;
using motion::Elbow;
using motion::kMaxSpeedFraction;
using motion::kMaxToolAngularSpeed;
using motion::kMaxToolSpeed;
using motion::kMinSpeedFraction;
using motion::kMinToolAngularSpeed;
using motion::kMinToolSpeed;

// What each move takes (docs/paths.md).
constexpr std::array<std::string_view, 13> kKeys = {"joints", "x",     "y",     "z",             "roll",
                                                     "pitch",  "yaw",   "elbow", "via",           "speed",
                                                     "zone",   "angular_speed", ""};

std::string_view allowed_keys(MoveKind kind) {
  switch (kind) {
    case MoveKind::ptp: return "joints, or x, y, z with roll, pitch, yaw, elbow; speed (N%)";
    case MoveKind::lin: return "x, y, z, roll, pitch, yaw, speed, angular_speed, zone";
    case MoveKind::circ: return "via, x, y, z, roll, pitch, yaw, speed, angular_speed, zone";
  }
  return "";
}

bool allowed(MoveKind kind, std::string_view key) {
  if (key == "x" || key == "y" || key == "z" || key == "roll" || key == "pitch" || key == "yaw" || key == "speed")
    return true;
  if (key == "joints" || key == "elbow") return kind == MoveKind::ptp;
  if (key == "zone" || key == "angular_speed") return kind != MoveKind::ptp;
  if (key == "via") return kind == MoveKind::circ;
  return false;
}

class Parser {
 public:
  explicit Parser(std::string_view source) : source_(source) {}

  Result<PathFile> parse(std::string_view text) {
    PathFile file;
    const auto last = read_lines(text, [&](const TextLine& line) -> Status {
      const auto& fields = line.fields;
      if (file.moves.size() == kPathFileMaxMoves)
        return fail(line.number, fields[0].column, fields[0].text,
                    fmt::format("at most {} moves in a path file", kPathFileMaxMoves));
      auto move = parse_move(line.number, fields);
      if (!move) return move.error();
      file.moves.push_back(std::move(move).value());
      return Ok{};
    });
    if (!last) return last.error();
    if (file.moves.empty())
      return Error{ErrorKind::invalid_config,
                   fmt::format("{}: the file has no moves; expected lines of ptp, lin or circ moves", printable(source_))};
    return file;
  }

 private:
  Error fail(std::size_t line, std::size_t column, std::string_view found, const std::string& expected) const {
    return file_error(source_, line, column, fmt::format("found '{}', expected {}", shown(found), expected));
  }
  // An error from a value parser (parse_quantity's message names the key, the text and the units).
  Error fail_value(std::size_t line, std::size_t column, const Error& e) const {
    return file_error(source_, line, column, shown(e.message, 400));
  }

  Result<double> quantity(std::size_t line, const Field& f, std::string_view key, std::string_view value,
                          Dimension d, int per_second) const {
    auto v = parse_quantity(value, d, key, per_second);
    if (!v) return fail_value(line, f.column + key.size() + 1, v.error());
    return v;
  }

 public:
  Result<PathMove> parse_move(std::size_t line, std::span<const Field> fields) {
    PathMove move;
    move.line = line;
    const std::string kind = ascii_lower(fields[0].text);
    if (kind == "ptp") move.kind = MoveKind::ptp;
    else if (kind == "lin") move.kind = MoveKind::lin;
    else if (kind == "circ") move.kind = MoveKind::circ;
    else return fail(line, fields[0].column, fields[0].text, "a move: ptp, lin or circ");
    std::array<bool, kKeys.size()> seen{};
    std::array<bool, 3> has_xyz{};
    bool has_via = false;
    for (std::size_t i = 1; i < fields.size(); ++i) {
      const Field& f = fields[i];
      const auto eq = f.text.find('=');
      if (eq == std::string_view::npos || eq == 0)
        return fail(line, f.column, f.text, fmt::format("key=value; a {} takes {}", to_string(move.kind),
                                                        allowed_keys(move.kind)));
      const std::string_view key = f.text.substr(0, eq), value = f.text.substr(eq + 1);
      const auto known = std::find(kKeys.begin(), kKeys.end() - 1, key);
      if (known == kKeys.end() - 1 || !allowed(move.kind, key))
        return fail(line, f.column, key, fmt::format("a key a {} takes: {}", to_string(move.kind),
                                                     allowed_keys(move.kind)));
      bool& once = seen[std::size_t(known - kKeys.begin())];
      if (once) return fail(line, f.column, key, "each key once per line");
      once = true;
      if (value.empty()) return fail(line, f.column + eq + 1, "", fmt::format("a value after '{}='", key));
      if (auto ok = parse_field(line, f, key, value, move, has_xyz, has_via); !ok) return ok.error();
    }
    return finish_move(line, fields, move, has_xyz, has_via);
  }

 private:
  Status parse_field(std::size_t line, const Field& f, std::string_view key, std::string_view value, PathMove& move,
                     std::array<bool, 3>& has_xyz, bool& has_via) const {
    const std::size_t value_column = f.column + key.size() + 1;
    if (key == "x" || key == "y" || key == "z") {
      auto v = quantity(line, f, key, value, Dimension::length, 0);
      if (!v) return v.error();
      const int axis = key[0] - 'x';
      move.position[axis] = *v;
      has_xyz[std::size_t(axis)] = true;
    } else if (key == "roll" || key == "pitch" || key == "yaw") {
      auto v = quantity(line, f, key, value, Dimension::angle, 0);
      if (!v) return v.error();
      (key == "roll" ? move.roll : key == "pitch" ? move.pitch : move.yaw) = *v;
    } else if (key == "via") {
      auto parts = list(value);
      if (parts.size() != 3)
        return fail(line, value_column, value, "three lengths x,y,z for via (e.g. via=250mm,150mm,150mm)");
      for (std::size_t k = 0; k < 3; ++k) {
        auto v = parse_quantity(parts[k].first, Dimension::length, "via", 0);
        if (!v) return fail_value(line, value_column + parts[k].second, v.error());
        move.via[Eigen::Index(k)] = *v;
      }
      has_via = true;
    } else if (key == "joints") {
      auto parts = list(value);
      if (parts.size() > kPathFileMaxJoints)
        return fail(line, value_column, value, fmt::format("at most {} joint values", kPathFileMaxJoints));
      for (const auto& [text, offset] : parts) {
        const std::size_t column = value_column + offset;
        if (text.empty()) return fail(line, column, "", "a joint value between the commas (e.g. 30deg or 120mm)");
        auto angle = parse_quantity(text, Dimension::angle, "joint value", 0);
        if (angle) {
          move.joints.push_back({*angle, Dimension::angle});
          continue;
        }
        auto length = parse_quantity(text, Dimension::length, "joint value", 0);
        if (!length)
          return fail(line, column, text, "a joint value: a number with deg or rad (revolute), mm or m (prismatic)");
        move.joints.push_back({*length, Dimension::length});
      }
    } else if (key == "elbow") {
      const std::string e = ascii_lower(value);
      if (e == "up") move.elbow = Elbow::up;
      else if (e == "down") move.elbow = Elbow::down;
      else if (e == "left") move.elbow = Elbow::left;
      else if (e == "right") move.elbow = Elbow::right;
      else return fail(line, value_column, value, "elbow up or down (xArm), left or right (SCARA)");
    } else if (key == "speed") {
      if (move.kind == MoveKind::ptp) {
        auto p = parse_percent(value, "speed", kMinSpeedFraction, kMaxSpeedFraction);
        if (!p)
          return fail(line, value_column, value,
                      fmt::format("a ptp speed in percent of the joints' velocity limits, {:g}..{:g} % (e.g. 50%)",
                                  kMinSpeedFraction * 100, kMaxSpeedFraction * 100));
        move.speed_fraction = *p;
      } else {
        if (!value.empty() && value.back() == '%')
          return fail(line, value_column, value,
                      fmt::format("the tool's speed for a {} (e.g. 50mm/s); a percent is for ptp", to_string(move.kind)));
        auto v = quantity(line, f, key, value, Dimension::length, 1);
        if (!v) return v.error();
        if (!(*v >= kMinToolSpeed && *v <= kMaxToolSpeed))
          return fail(line, value_column, value,
                      fmt::format("a speed within {} (e.g. 50mm/s)", shown_range(Dimension::length, kMinToolSpeed, kMaxToolSpeed)));
        move.speed = *v;
      }
    } else if (key == "angular_speed") {
      auto v = quantity(line, f, key, value, Dimension::angle, 1);
      if (!v) return v.error();
      if (!(*v >= kMinToolAngularSpeed && *v <= kMaxToolAngularSpeed))
        return fail(line, value_column, value,
                    fmt::format("an angular speed within {} (e.g. 30deg/s)",
                                shown_range(Dimension::angle, kMinToolAngularSpeed, kMaxToolAngularSpeed)));
      move.angular_speed = *v;
    } else if (key == "zone") {
      auto v = quantity(line, f, key, value, Dimension::length, 0);
      if (!v) return v.error();
      if (!(*v >= 0)) return fail(line, value_column, value, "a zone >= 0 (e.g. 5mm; 0 stops exactly at the target)");
      move.zone = *v;
    }
    return Ok{};
  }

  Result<PathMove> finish_move(std::size_t line, std::span<const Field> fields, PathMove& move,
                               const std::array<bool, 3>& has_xyz, bool has_via) const {
    const Field& first = fields[0];
    const std::size_t after = fields.back().column + fields.back().text.size();
    const bool any_xyz = has_xyz[0] || has_xyz[1] || has_xyz[2];
    const bool any_rpy = move.roll || move.pitch || move.yaw;
    if (move.kind == MoveKind::ptp && !move.joints.empty()) {
      if (any_xyz || any_rpy || move.elbow)
        return fail(line, first.column, first.text,
                    "a ptp to joints (joints=...) or to a pose (x, y, z ...), not both");
      return move;
    }
    if (move.kind == MoveKind::ptp && !any_xyz && !any_rpy && !move.elbow)
      return fail(line, after, "", "the ptp's target: joints=... or x=, y=, z=");
    for (int k = 0; k < 3; ++k)
      if (!has_xyz[std::size_t(k)])
        return fail(line, after, "",
                    fmt::format("{}=: a {} needs the tool's position x, y and z", char('x' + k), to_string(move.kind)));
    if (move.kind == MoveKind::circ && !has_via)
      return fail(line, after, "", "via=x,y,z: a circ needs a point on the arc between start and target");
    return move;
  }

  // "0.1..500 mm/s": a speed range for people.
  static std::string shown_range(Dimension d, double min_si, double max_si) {
    return fmt::format("{:g}..{:g} {}/s", to_display(d, min_si), to_display(d, max_si), display_unit(d));
  }

  // Comma-separated parts with their offsets in `value`.
  static std::vector<std::pair<std::string_view, std::size_t>> list(std::string_view value) {
    std::vector<std::pair<std::string_view, std::size_t>> parts;
    std::size_t start = 0;
    while (parts.size() <= kPathFileMaxJoints) {
      const std::size_t comma = value.find(',', start);
      parts.push_back({value.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start),
                       start});
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return parts;
  }

  std::string source_;
};

std::string si(double v) { return fmt::format("{}", v); }

}  // namespace

const char* to_string(MoveKind kind) {
  switch (kind) {
    case MoveKind::ptp: return "ptp";
    case MoveKind::lin: return "lin";
    case MoveKind::circ: return "circ";
  }
  return "?";
}

Result<PathFile> parse_path_file(std::string_view text, std::string_view source) {
  if (text.size() > json_reader::kMaxConfigBytes)
    return Error{ErrorKind::invalid_config,
                 fmt::format("{}: {} bytes is larger than a path file may be (1 MiB)", printable(source), text.size())};
  return Parser(source).parse(text);
}

Result<PathMove> parse_path_move(std::span<const TextField> fields, std::size_t line, std::string_view source) {
  return Parser(source).parse_move(line, fields);
}

Result<PathFile> read_path_file(const std::filesystem::path& path) {
  auto text = catch_error([&]() -> Result<std::string> { return json_reader::read_config_file(path, "path file"); });
  if (!text) return text.error();
  return parse_path_file(*text, path.string());
}

std::string format_path_file(const PathFile& file) {
  std::string out = "# armctl path: ptp | lin | circ, then key=value fields (docs/paths.md)\n";
  for (const PathMove& m : file.moves) {
    out += to_string(m.kind);
    if (m.kind == MoveKind::ptp && !m.joints.empty()) {
      out += " joints=";
      for (std::size_t i = 0; i < m.joints.size(); ++i)
        out += (i ? "," : "") + si(m.joints[i].value) + (m.joints[i].dimension == Dimension::angle ? "rad" : "m");
    } else {
      if (m.kind == MoveKind::circ)
        out += fmt::format(" via={}m,{}m,{}m", si(m.via.x()), si(m.via.y()), si(m.via.z()));
      out += fmt::format(" x={}m y={}m z={}m", si(m.position.x()), si(m.position.y()), si(m.position.z()));
      if (m.roll) out += " roll=" + si(*m.roll) + "rad";
      if (m.pitch) out += " pitch=" + si(*m.pitch) + "rad";
      if (m.yaw) out += " yaw=" + si(*m.yaw) + "rad";
      if (m.elbow) out += std::string(" elbow=") + to_string(*m.elbow);
    }
    if (m.speed_fraction) out += " speed=" + si(*m.speed_fraction * 100) + "%";
    if (m.speed) out += " speed=" + si(*m.speed) + "m/s";
    if (m.angular_speed) out += " angular_speed=" + si(*m.angular_speed) + "rad/s";
    if (m.zone > 0) out += " zone=" + si(m.zone) + "m";
    out += "\n";
  }
  return out;
}

}  // namespace armctl::files

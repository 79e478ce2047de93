#include "files/points_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>

#include <fmt/core.h>

#include "core/ascii.hpp"
#include "core/atomic_file.hpp"
#include "core/json_reader.hpp"
#include "core/regular_file.hpp"
#include "files/language_words.hpp"
#include "files/line_reader.hpp"

namespace armctl::files {

namespace {


constexpr std::string_view kPointKeys = "joints=..., or x, y, z with roll, pitch, yaw, elbow";

Error fail(std::string_view source, std::size_t line, std::size_t column, std::string_view found,
           const std::string& expected) {
  return file_error(source, line, column, fmt::format("found '{}', expected {}", shown(found), expected));
}

// The path file's parser reads a point's fields (they are a ptp's target): its words speak
// of a ptp.
Error from_path_error(const Error& e) {
  const SourcePlace* where = source_place(e);
  if (!where) return Error{ErrorKind::invalid_config, e.message};
  SourcePlace place = *where;
  std::string& m = place.reason;
  for (auto [from, to] : {std::pair<std::string_view, std::string_view>{"a ptp", "a point"}, {"the ptp's", "the point's"}}) {
    for (auto at = m.find(from); at != std::string::npos; at = m.find(from, at + to.size())) m.replace(at, from.size(), to);
  }
  return source_error(ErrorKind::invalid_config, std::move(place));
}

// Shortest digits that read back as the same double.
std::string number(double v) { return fmt::format("{}", v == 0 ? 0.0 : v); }

}  // namespace

bool is_language_word(std::string_view word) {
  const std::string w = ascii_lower(word);
  return std::find(kLanguageWords.begin(), kLanguageWords.end(), w) != kLanguageWords.end();
}

std::optional<std::string> bad_name(std::string_view name) {
  if (name.empty()) return "a name cannot be empty";
  if (name.size() > kPointNameMaxLength) return fmt::format("a name has at most {} characters", kPointNameMaxLength);
  const auto letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
  if (!letter(name[0])) return "a name starts with a letter or '_'";
  for (char c : name)
    if (!letter(c) && !std::isdigit(static_cast<unsigned char>(c))) return "a name has only letters, digits and '_'";
  if (is_language_word(name)) return fmt::format("'{}' is a word of the program language", ascii_lower(name));
  return std::nullopt;
}

const Point* PointsFile::find(std::string_view name) const {
  for (const Point& p : points)
    if (p.name == name) return &p;
  return nullptr;
}

Result<PointsFile> parse_points_file(std::string_view text, std::string_view source) {
  PointsFile file;
  std::set<std::string, std::less<>> names;
  LineReader lines(text);
  while (auto text_line = lines.next()) {
    const std::size_t line_no = text_line->number;
    {
      const std::size_t name_start = text_line->fields[0].column - 1;
      const std::string_view name = text_line->fields[0].text;
      const std::size_t i = name_start + name.size();
      if (name.find('=') != std::string_view::npos)
        return fail(source, line_no, name_start + 1, name, "a point's name first (e.g. 'pick x=200mm y=0mm z=40mm')");
      if (auto why = bad_name(name)) return fail(source, line_no, name_start + 1, name, "a point name: " + *why);
      if (names.contains(name)) return fail(source, line_no, name_start + 1, name, "each point name once");
      if (file.points.size() == kPointsFileMaxPoints)
        return fail(source, line_no, name_start + 1, name, fmt::format("at most {} points in a file", kPointsFileMaxPoints));
      // Only the keys of a point (a ptp would also take speed).
      std::vector<TextField> fields = text_line->fields;
      for (std::size_t k = 1; k < fields.size(); ++k) {
        const std::string_view field = fields[k].text;
        const std::string_view key = field.substr(0, field.find('='));
        static constexpr std::string_view kKeys[] = {"joints", "x", "y", "z", "roll", "pitch", "yaw", "elbow"};
        if (field.find('=') == std::string_view::npos || std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys))
          return fail(source, line_no, fields[k].column, field.find('=') == std::string_view::npos ? field : key,
                      fmt::format("a point's key=value: {}", kPointKeys));
      }
      if (fields.size() == 1)
        return fail(source, line_no, i + 1, "", fmt::format("the point's position after its name: {}", kPointKeys));
      fields[0].text = "ptp";  // the fields after the name read as a ptp's target
      auto parsed = parse_path_move(fields, line_no, source);
      if (!parsed) return from_path_error(parsed.error());
      const PathMove& m = *parsed;
      Point p;
      p.name = std::string(name);
      p.line = line_no;
      p.joints = m.joints;
      if (p.joints.empty()) {
        p.position = m.position;
        p.roll = m.roll;
        p.pitch = m.pitch;
        p.yaw = m.yaw;
        p.elbow = m.elbow;
      }
      names.insert(p.name);
      file.points.push_back(std::move(p));
    }
  }
  return file;
}

Result<PointsFile> read_points_file(const std::filesystem::path& path) {
  auto text = catch_error([&]() -> Result<std::string> { return json_reader::read_config_file(path, "points file"); });
  if (!text) return text.error();
  return parse_points_file(*text, path.string());
}

std::string format_point_fields(const Point& p) {
  constexpr double kDeg = 180 / M_PI;
  std::string out;
  if (p.is_joints()) {
    out += "joints=";
    for (std::size_t i = 0; i < p.joints.size(); ++i) {
      const auto& j = p.joints[i];
      out += (i ? "," : "") +
             (j.dimension == Dimension::angle ? number(j.value * kDeg) + "deg" : number(j.value * 1e3) + "mm");
    }
  } else {
    out += fmt::format("x={}mm y={}mm z={}mm", number(p.position.x() * 1e3), number(p.position.y() * 1e3),
                       number(p.position.z() * 1e3));
    if (p.roll) out += " roll=" + number(*p.roll * kDeg) + "deg";
    if (p.pitch) out += " pitch=" + number(*p.pitch * kDeg) + "deg";
    if (p.yaw) out += " yaw=" + number(*p.yaw * kDeg) + "deg";
    if (p.elbow) out += std::string(" elbow=") + motion::to_string(*p.elbow);
  }
  return out;
}

namespace {

std::size_t name_width(const PointsFile& file) {
  std::size_t width = 0;
  for (const Point& p : file.points) width = std::max(width, p.name.size());
  return width;
}

bool same_value(Point a, const Point& b) {
  a.line = b.line;
  return a == b;
}

}  // namespace

std::string format_points_file(const PointsFile& file) {
  std::string out = "# armctl points: NAME joints=... | NAME x= y= z= [roll= pitch= yaw= elbow=] (docs/programs.md)\n";
  const std::size_t width = name_width(file);
  for (const Point& p : file.points) out += fmt::format("{:<{}} {}\n", p.name, width, format_point_fields(p));
  return out;
}

Result<std::string> update_points_text(std::string_view text, const PointsFile& file, std::string_view source) {
  const std::string_view bom = text.starts_with(kUtf8Bom) ? kUtf8Bom : std::string_view();
  text.remove_prefix(bom.size());
  auto old = parse_points_file(text, source);
  if (!old)
    return Error{old.error().kind, fmt::format("{}; the file is left as it is (fix it, then save again)", old.error().message)};
  std::string out(bom);
  std::set<std::string, std::less<>> kept;
  std::size_t pos = 0, line_no = 0;
  auto point = old->points.begin();  // in line order, as parsed
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    end = end == std::string_view::npos ? text.size() : end + 1;
    const std::string_view line = text.substr(pos, end - pos);
    pos = end;
    ++line_no;
    if (point == old->points.end() || point->line != line_no) {
      out += line;  // a comment, a blank line
      continue;
    }
    const Point& was = *point++;
    const Point* now = file.find(was.name);
    if (now == nullptr) continue;  // deleted: its line goes
    kept.insert(was.name);
    if (same_value(*now, was)) {
      out += line;
      continue;
    }
    // The fields between the name (and the blanks after it) and the last field; the
    // indentation, the alignment, a trailing comment and the line's end stay.
    const std::string_view code = line.substr(0, std::min(line.find('#'), line.size()));
    std::size_t from = 0;
    while (from < code.size() && is_blank(code[from])) ++from;
    from += was.name.size();
    while (from < code.size() && is_blank(code[from])) ++from;
    std::size_t to = code.size();
    while (to > from && (is_blank(code[to - 1]) || code[to - 1] == '\n')) --to;
    out += line.substr(0, from);
    out += format_point_fields(*now);
    out += line.substr(to);
  }
  // New points at the end, in the file's line ending, their names padded as the writer does.
  const std::size_t first_newline = text.find('\n');
  const std::string_view newline =
      first_newline != std::string_view::npos && first_newline > 0 && text[first_newline - 1] == '\r' ? "\r\n" : "\n";
  const std::size_t width = name_width(file);
  for (const Point& p : file.points) {
    if (kept.contains(p.name)) continue;
    if (!out.empty() && out.back() != '\n') out += newline;
    out += fmt::format("{:<{}} {}{}", p.name, width, format_point_fields(p), newline);
  }
  return out;
}

Status write_points_file(const std::filesystem::path& path, const PointsFile& file) {
  for (const Point& p : file.points)
    if (auto why = bad_name(p.name)) return Error{ErrorKind::invalid_argument, fmt::format("point '{}': {}", shown(p.name), *why)};
  // A file that is there is updated in its own words; read as it is (byte-order mark kept).
  std::string text;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    auto old = read_regular_file(path, "points file", json_reader::kMaxConfigBytes);
    if (!old) return old.error();
    auto updated = update_points_text(*old, file, path.string());
    if (!updated) return updated.error();
    text = std::move(updated).value();
  } else {
    text = format_points_file(file);
  }
  return write_file_atomically(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace armctl::files

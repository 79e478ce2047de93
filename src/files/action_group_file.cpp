#include "files/action_group_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include <fmt/core.h>

#include "core/printable.hpp"
#include "core/regular_file.hpp"
#include "files/line_reader.hpp"
#include "protocol/robot_commands/units.hpp"

namespace armctl::files {
namespace {

using Field = TextField;

std::optional<long> whole_number(std::string_view s) {
  long value = 0;
  if (s.empty() || s.size() > 9) return std::nullopt;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc{} || p != s.data() + s.size()) return std::nullopt;
  return value;
}

std::optional<double> decimal_number(std::string_view s) {
  double value = 0;
  if (s.empty() || s.size() > 16) return std::nullopt;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc{} || p != s.data() + s.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

class Parser {
 public:
  explicit Parser(std::string_view source) : source_(source) {}

  Result<ActionGroupFile> parse(std::string_view text) {
    const auto last = read_lines(text, [&](const TextLine& line) -> Status {
      if (auto e = parse_line(line.number, line.fields)) return *e;
      return Ok{};
    });
    if (!last) return last.error();
    const std::size_t line_no = *last;
    if (group_.actions.empty())
      return fail(line_no, 0, "", "the file has no actions; a group holds 1..1020");
    if (header_count_ && *header_count_ != group_.servos.size())
      return fail(header_line_, 0, "",
                  fmt::format("header says {} servos but the actions name {}", *header_count_,
                              group_.servos.size()));
    return group_;
  }

 private:
  Error fail(std::size_t line, std::size_t column, std::string_view field,
             const std::string& what) const {
    // The file's name and fields are outside text: printable() keeps control sequences in
    // them from reaching a terminal.
    std::string shown = field.empty() ? "" : fmt::format("'{}' ", printable(field));
    return file_error(source_, line, column, shown + what);
  }

  std::optional<Error> parse_line(std::size_t line, const std::vector<Field>& fields) {
    if (fields[0].text == "servos") return parse_header(line, fields);
    return parse_action(line, fields);
  }

  std::optional<Error> parse_header(std::size_t line, const std::vector<Field>& fields) {
    if (header_count_) return fail(line, fields[0].column, "servos", "a second 'servos' header");
    if (!group_.actions.empty())
      return fail(line, fields[0].column, "servos",
                  "the 'servos' header must come before the "
                  "first action");
    if (fields.size() != 2)
      return fail(line, fields[0].column, "servos", "expected 'servos N' with N in 1..17");
    auto n = whole_number(fields[1].text);
    if (!n || *n < 1 || *n > static_cast<long>(kGroupFileMaxServos))
      return fail(line, fields[1].column, fields[1].text, "servo count must be 1..17");
    header_count_ = static_cast<std::size_t>(*n);
    header_line_ = line;
    return std::nullopt;
  }

  std::optional<Error> parse_action(std::size_t line, const std::vector<Field>& fields) {
    if (group_.actions.size() == kGroupFileMaxActions)
      return fail(line, fields[0].column, "", "more than 1020 actions (the most a group holds)");
    std::string_view time_text = fields[0].text;
    if (time_text.size() > 2 && time_text.substr(time_text.size() - 2) == "ms")
      time_text.remove_suffix(2);
    auto ms = whole_number(time_text);
    if (!ms || *ms < 0 || *ms > rc::kMoveTimeMaxMs)
      return fail(line, fields[0].column, fields[0].text,
                  "time must be whole milliseconds 0..30000 (e.g. 1000 or 1000ms)");
    if (fields.size() == 1)
      return fail(line, fields[0].column + fields[0].text.size(), "",
                  "an action needs at least one servo=position after its time");
    rc::GroupAction action;
    action.time_ms = static_cast<std::uint16_t>(*ms);
    for (std::size_t i = 1; i < fields.size(); ++i) {
      auto target = parse_target(line, fields[i]);
      if (!target) return target.error();
      for (const auto& t : action.targets)
        if (t.servo == target->servo)
          return fail(line, fields[i].column, fields[i].text,
                      fmt::format("servo {} appears twice in this action", t.servo));
      action.targets.push_back(*target);
    }
    if (action.targets.size() > kGroupFileMaxServos)
      return fail(line, fields[0].column, "",
                  fmt::format("{} servos in one action; at most 17", action.targets.size()));
    if (auto e = check_servo_set(line, fields, action)) return e;
    group_.actions.push_back(std::move(action));
    return std::nullopt;
  }

  std::optional<Error> check_servo_set(std::size_t line, const std::vector<Field>& fields,
                                       const rc::GroupAction& action) {
    if (group_.actions.empty()) {
      for (const auto& t : action.targets) group_.servos.push_back(t.servo);
      if (header_count_ && *header_count_ != group_.servos.size())
        return fail(line, fields[0].column, "",
                    fmt::format("this action names {} servos but the header says {}",
                                group_.servos.size(), *header_count_));
      return std::nullopt;
    }
    for (std::size_t i = 0; i < action.targets.size(); ++i) {
      std::uint8_t id = action.targets[i].servo;
      if (std::find(group_.servos.begin(), group_.servos.end(), id) == group_.servos.end())
        return fail(line, fields[i + 1].column, fields[i + 1].text,
                    fmt::format("servo {} is not in this group's servo set {} (every action "
                                "names the same servos)",
                                id, servo_set_text()));
    }
    if (action.targets.size() != group_.servos.size())
      return fail(line, fields[0].column, "",
                  fmt::format("this action names {} servos but every action must name the "
                              "same {}: {}",
                              action.targets.size(), group_.servos.size(), servo_set_text()));
    return std::nullopt;
  }

  std::string servo_set_text() const {
    std::string s;
    for (std::uint8_t id : group_.servos) s += (s.empty() ? "" : ",") + std::to_string(id);
    return s;
  }

  Result<rc::ServoTarget> parse_target(std::size_t line, const Field& field) {
    auto eq = field.text.find('=');
    if (eq == std::string_view::npos)
      return fail(line, field.column, field.text, "expected servo=position (e.g. 1=500)");
    auto id = whole_number(field.text.substr(0, eq));
    if (!id || *id < 1 || *id > 254)
      return fail(line, field.column, field.text, "servo ID must be a whole number 1..254");
    std::string_view value = field.text.substr(eq + 1);
    rc::ServoTarget target;
    target.servo = static_cast<std::uint8_t>(*id);
    if (value == "keep") return target;
    if (value.size() > 3 && value.substr(value.size() - 3) == "deg") {
      auto deg = decimal_number(value.substr(0, value.size() - 3));
      if (!deg || *deg < -120.0 || *deg > 120.0)
        return fail(line, field.column + eq + 1, field.text,
                    "degrees must be -120..120 from centre (e.g. 30deg, -12.5deg)");
      target.position = static_cast<std::uint16_t>(rc::degrees_to_position(*deg));
      return target;
    }
    auto p = whole_number(value);
    if (!p || *p < 0 || *p > 1000)
      return fail(line, field.column + eq + 1, field.text,
                  "position must be 0..1000, degrees like 30deg (-120..120), or keep");
    target.position = static_cast<std::uint16_t>(*p);
    return target;
  }

  std::string_view source_;
  ActionGroupFile group_;
  std::optional<std::size_t> header_count_;
  std::size_t header_line_ = 0;
};

}  // namespace

Result<ActionGroupFile> parse_action_group(std::string_view text, std::string_view source) {
  return Parser(source).parse(text);
}

Result<ActionGroupFile> read_action_group_file(const std::filesystem::path& path) {
  // 1,020 actions of 17 servos take about 100 kB; 1 MiB leaves room for comments. A
  // directory or FIFO is refused at once instead of reading as "no actions" or blocking.
  constexpr std::uintmax_t kMaxGroupFileBytes = 1 << 20;
  auto text = read_text_file(path, "group file", kMaxGroupFileBytes);
  if (!text) return text.error();
  return parse_action_group(*text, path.string());
}

std::string format_action_group(const ActionGroupFile& group) {
  std::string out = "# armctl action group: time_ms servo=position ... (0..1000, NNdeg or keep)\n";
  out += fmt::format("servos {}\n", group.servos.size());
  for (const auto& action : group.actions) {
    out += std::to_string(action.time_ms);
    for (const auto& t : action.targets)
      out += t.position ? fmt::format(" {}={}", t.servo, *t.position)
                        : fmt::format(" {}=keep", t.servo);
    out += '\n';
  }
  return out;
}

}  // namespace armctl::files

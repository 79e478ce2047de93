// The one reader under every line-oriented file armctl reads (action groups, paths, points,
// recordings): lines numbered from 1, '#' to the end of a line a comment, blank and
// comment-only lines skipped, a line's blank-separated fields with their 1-based columns, and
// a Windows line end ("\r\n") read as a plain one. Each format is a small parser of the
// fields on top; the places in its errors are SourcePlaces (core/source_place.hpp).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/source_place.hpp"

namespace armctl::files {

struct TextField {
  std::string_view text;
  std::size_t column;  // 1-based
};

// Blanks are spaces, tabs and a stray '\r' (files written on Windows).
inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// `line`'s blank-separated fields.
std::vector<TextField> split_fields(std::string_view line);

// One line that holds something besides blanks and a comment.
struct TextLine {
  std::size_t number = 0;       // from 1
  std::string_view code;        // the line before its '#' (and before its "\n")
  std::vector<TextField> fields;  // code's fields, never empty
};

class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  // The next line with a field, or nullopt at the end of the text.
  std::optional<TextLine> next();
  // The number of the last line read (for "the file ends here" errors): the text's last
  // line once next() has returned nullopt.
  std::size_t line_number() const { return line_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
  bool done_ = false;
};

// Calls `take` on every line with a field, in order, up to the first error, which it returns;
// else the number of the text's last line (for "the file ends here" errors).
template <typename Take>
Result<std::size_t> read_lines(std::string_view text, Take&& take) {
  LineReader lines(text);
  while (auto line = lines.next())
    if (Status s = take(*line); !s) return s.error();
  return lines.line_number();
}

// Outside text quoted in a message: control bytes escaped (core/printable.hpp), so one bad
// byte in a file cannot garble the terminal, and long text cut ("...").
std::string shown(std::string_view text, std::size_t longest = 60);

// The invalid_config error "source:line:column: reason" with its SourcePlace (column 0: the
// line as a whole). `source` is outside text: it is passed through printable().
Error file_error(std::string_view source, std::size_t line, std::size_t column, std::string reason);

}  // namespace armctl::files

// The one line reader under every text file format: numbering, comments, blank lines,
// Windows line ends, fields with their columns, and the errors' places.
#include "files/line_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/source_place.hpp"

namespace armctl::files {
namespace {

// "number:field@column field@column" per line read.
std::vector<std::string> read_all(std::string_view text) {
  std::vector<std::string> out;
  LineReader lines(text);
  while (auto line = lines.next()) {
    std::string s = std::to_string(line->number) + ":";
    for (const TextField& f : line->fields) s += " " + std::string(f.text) + "@" + std::to_string(f.column);
    out.push_back(s);
  }
  return out;
}

TEST(LineReader, NumbersLinesAndSkipsBlankAndCommentLines) {
  EXPECT_EQ(read_all("a b\n\n  # note\n\tc  d # tail\n"),
            (std::vector<std::string>{"1: a@1 b@3", "4: c@2 d@5"}));
}

TEST(LineReader, ReadsWindowsLineEndsAsPlainOnes) {
  EXPECT_EQ(read_all("a b\r\n\r\nc\r\n"), (std::vector<std::string>{"1: a@1 b@3", "3: c@1"}));
}

TEST(LineReader, CountsTheLastLineForEndOfFileErrors) {
  for (const auto& [text, last] : std::vector<std::pair<std::string, std::size_t>>{
           {"", 1}, {"a", 1}, {"a\n", 2}, {"a\n\n# c", 3}}) {
    LineReader lines(text);
    while (lines.next()) {
    }
    EXPECT_EQ(lines.line_number(), last) << text;
  }
}

TEST(LineReader, ACommentMayHoldAnything) {
  EXPECT_EQ(read_all("x # a=b # c\n#\n"), (std::vector<std::string>{"1: x@1"}));
}

TEST(LineReader, ErrorsCarryTheirPlaceAndShowOutsideTextEscaped) {
  const Error e = file_error("in\x1b.txt", 3, 7, "found 'q', expected a number");
  EXPECT_EQ(e.kind, ErrorKind::invalid_config);
  EXPECT_EQ(e.message, "in\\x1b.txt:3:7: found 'q', expected a number");
  const SourcePlace* place = source_place(e);
  ASSERT_NE(place, nullptr);
  EXPECT_EQ(place->line, 3u);
  EXPECT_EQ(place->column, 7u);
  EXPECT_EQ(file_error("f", 2, 0, "empty").message, "f:2: empty");
  EXPECT_EQ(shown("ab\x07" "cdef", 4), "ab\\x07c...");
}

}  // namespace
}  // namespace armctl::files

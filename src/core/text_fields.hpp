// Splits one line of a line-oriented file (path files, action group files) into its
// blank-separated fields, each with its 1-based column for error messages.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

namespace armctl {

struct TextField {
  std::string_view text;
  std::size_t column;  // 1-based
};

// Blanks are spaces, tabs and a stray '\r' (files written on Windows).
inline std::vector<TextField> split_fields(std::string_view line) {
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  std::vector<TextField> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !blank(line[i])) ++i;
    if (i > start) fields.push_back({line.substr(start, i - start), start + 1});
  }
  return fields;
}

}  // namespace armctl

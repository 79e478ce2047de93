// The parser of robot programs (the language: docs/programs.md). Text in, a syntax tree
// out; every error names the file, line and column, what was found and what was expected.
// Pure: no I/O except read_program_file.
#pragma once

#include <filesystem>
#include <string_view>

#include "core/error.hpp"
#include "program/program_syntax.hpp"

namespace armctl::program {

inline constexpr std::size_t kProgramMaxBytes = 1 << 20;
inline constexpr std::size_t kProgramMaxNesting = 32;  // IF/LOOP/WHILE inside one another
// One expression: parentheses, signs and NOTs inside one another, and binary operators in
// all (a chain "a + b + c" is parsed and evaluated by a loop, but a program never needs a
// thousand terms in one expression: split it over variables).
inline constexpr int kExpressionMaxNesting = 64;
inline constexpr int kExpressionMaxOperators = 1000;

// `source` names the text in errors ("pick.prog:12:5: found 'end', expected ...").
Result<Program> parse_program(std::string_view text, std::string_view source = "<program>");
Result<Program> read_program_file(const std::filesystem::path& path);

}  // namespace armctl::program

// Tokens of the program language: names, numbers with their unit, strings, operators and
// line ends. '#' starts a comment to the end of the line.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "program/program_syntax.hpp"

namespace armctl::program {

enum class TokenKind { name, number, string, symbol, newline, end_of_file };

struct Token {
  TokenKind kind = TokenKind::end_of_file;
  Place at;
  std::string text;  // as written (a string: its content)
  Value value;       // number
};

// For messages: "'lin'", "the end of the line", "the end of the file".
std::string describe(const Token& t);

Result<std::vector<Token>> lex_program(std::string_view text, std::string_view source);

}  // namespace armctl::program

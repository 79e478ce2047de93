#include "program/program_lexer.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

#include <fmt/core.h>

#include "core/source_place.hpp"
#include "core/printable.hpp"

namespace armctl::program {

namespace {

// Outside text for messages: control bytes escaped (core/printable.hpp), long text cut.
std::string shown(std::string_view text, std::size_t longest = 40) {
  return printable(text.substr(0, longest)) + (text.size() > longest ? "..." : "");
}

bool letter(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

}  // namespace

std::string describe(const Token& t) {
  switch (t.kind) {
    case TokenKind::newline: return "the end of the line";
    case TokenKind::end_of_file: return "the end of the file";
    case TokenKind::string: return fmt::format("the text \"{}\"", shown(t.text));
    default: return fmt::format("'{}'", shown(t.text));
  }
}

Result<std::vector<Token>> lex_program(std::string_view text, std::string_view source) {
  std::vector<Token> out;
  std::size_t i = 0, line = 1, line_start = 0;
  auto place = [&](std::size_t at) { return Place{line, at - line_start + 1}; };
  auto fail = [&](std::size_t at, std::string_view found, std::string_view expected) {
    return source_error(ErrorKind::invalid_config, {std::string(source), line, at - line_start + 1,
                                                    fmt::format("found '{}', expected {}", shown(found), expected)});
  };
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '\n') {
      out.push_back({TokenKind::newline, place(i), "\n", {}});
      ++i;
      ++line;
      line_start = i;
    } else if (letter(c)) {
      const std::size_t start = i;
      while (i < text.size() && (letter(text[i]) || digit(text[i]))) ++i;
      out.push_back({TokenKind::name, place(start), std::string(text.substr(start, i - start)), {}});
    } else if (digit(c) || (c == '.' && i + 1 < text.size() && digit(text[i + 1]))) {
      const std::size_t start = i;
      while (i < text.size() && (digit(text[i]) || text[i] == '.')) ++i;
      if (i < text.size() && (text[i] == 'e' || text[i] == 'E') && i + 1 < text.size() &&
          (digit(text[i + 1]) || ((text[i + 1] == '-' || text[i + 1] == '+') && i + 2 < text.size() && digit(text[i + 2])))) {
        i += 2;
        while (i < text.size() && digit(text[i])) ++i;
      }
      const std::string_view digits = text.substr(start, i - start);
      double v = 0;
      auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
      if (ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(v))
        return fail(start, digits, "a number (e.g. 40, 2.5, 1e-3)");
      // The unit right after the number: letters, '%', and "/s" or "/s^2".
      const std::size_t unit_start = i;
      if (i < text.size() && text[i] == '%') {
        ++i;
      } else {
        while (i < text.size() && std::isalpha(static_cast<unsigned char>(text[i]))) ++i;
        if (i > unit_start && i + 1 < text.size() && text[i] == '/' && text[i + 1] == 's') {
          i += 2;
          if (i + 1 < text.size() && text[i] == '^' && digit(text[i + 1])) i += 2;
        }
      }
      Value value{v, Unit::number};
      if (i > unit_start) {
        const std::string_view unit = text.substr(unit_start, i - unit_start);
        auto suffix = unit_suffix(unit);
        if (!suffix) return fail(unit_start, unit, fmt::format("a unit after the number: {}", allowed_suffixes()));
        value = {v * suffix->factor, suffix->unit};
      }
      if (i < text.size() && (letter(text[i]) || digit(text[i])))
        return fail(start, text.substr(start, i + 1 - start),
                    fmt::format("a number with a unit ({}), then a space", allowed_suffixes()));
      out.push_back({TokenKind::number, place(start), std::string(text.substr(start, i - start)), value});
    } else if (c == '"') {
      const std::size_t start = i++;
      std::string s;
      while (i < text.size() && text[i] != '"' && text[i] != '\n') s += text[i++];
      if (i >= text.size() || text[i] != '"') return fail(start, text.substr(start, i - start), "a closing '\"' on the same line");
      ++i;
      out.push_back({TokenKind::string, place(start), s, {}});
    } else {
      static constexpr std::string_view kTwo[] = {"<=", ">=", "==", "!="};
      static constexpr std::string_view kOne = "()+-*/<>=,";
      bool matched = false;
      for (auto two : kTwo)
        if (text.substr(i, 2) == two) {
          out.push_back({TokenKind::symbol, place(i), std::string(two), {}});
          i += 2;
          matched = true;
          break;
        }
      if (!matched) {
        if (kOne.find(c) == std::string_view::npos)
          return fail(i, text.substr(i, 1), "a name, a number, a \"text\", an operator (+ - * / < <= > >= == !=) or ( ) , =");
        out.push_back({TokenKind::symbol, place(i), std::string(1, c), {}});
        ++i;
      }
    }
  }
  out.push_back({TokenKind::newline, place(i), "\n", {}});
  out.push_back({TokenKind::end_of_file, place(i), "", {}});
  return out;
}

}  // namespace armctl::program

// The reserved words of the program language (docs/programs.md), case-insensitive. They
// cannot name a point, a variable or a subroutine: here beside the points file, which
// refuses them as names, below the program layer that parses them.
#pragma once

#include <array>
#include <string_view>

namespace armctl::files {

inline constexpr std::array<std::string_view, 25> kLanguageWords = {
    "ptp", "lin",  "circ",     "wait", "gripper", "open", "close", "print", "if",   "then", "else", "end",
    "loop", "times", "while", "def",  "call",    "override", "and", "or",  "not",  "tool", "base",
    "joints", "pose"};

// `word` in lower case is one of kLanguageWords.
bool is_language_word(std::string_view word);

}  // namespace armctl::files

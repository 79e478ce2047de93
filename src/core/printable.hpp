// Outside text (file contents and names, config keys, device strings, CLI arguments) quoted
// in a message must not reach a terminal as control sequences: `ESC ]0;...BEL` in a group
// file would retitle the window, ESC [2J would clear it. Every message that quotes such text
// passes it through printable() first.
#pragma once

#include <string>
#include <string_view>

namespace armctl {

// `text` with newline, carriage return and tab written as \n, \r, \t and every other byte
// below 0x20, 0x7f, every C1 control (U+0080..U+009F, which some terminals obey too) and
// every byte that is not part of valid UTF-8 written as \xNN. Valid printable UTF-8 is kept
// as it is. Backslashes are kept too, so printable(printable(t)) == printable(t): a message
// may pass through it where it is made and again where it is printed.
std::string printable(std::string_view text);

}  // namespace armctl

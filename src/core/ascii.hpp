// Case-insensitive words in file formats and requests (keywords, joint names, Host headers):
// ASCII only, whatever the process's locale.
#pragma once

#include <string>
#include <string_view>

namespace armctl {

inline std::string ascii_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

}  // namespace armctl

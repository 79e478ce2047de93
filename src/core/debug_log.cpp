#include "core/debug_log.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace armctl {

bool debug_log_enabled() {
  const char* v = std::getenv("ARMCTL_DEBUG");
  return v != nullptr && std::string_view(v) != "" && std::string_view(v) != "0";
}

void debug_log(std::string_view line) {
  if (!debug_log_enabled()) return;
  const std::string text = "armctl: debug: " + std::string(line) + "\n";
  std::fputs(text.c_str(), stderr);
}

}  // namespace armctl

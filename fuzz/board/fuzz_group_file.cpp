// Arbitrary text into the action-group file parser: never a crash; anything accepted obeys
// the documented limits and survives a format/parse round trip unchanged.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "files/action_group_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl::files;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto g = parse_action_group(text, "fuzz");
  if (!g.ok()) {
    if (g.error().message.rfind("fuzz:", 0) != 0) std::abort();  // errors name the line
    return 0;
  }
  if (g->actions.empty() || g->actions.size() > kGroupFileMaxActions) std::abort();
  for (const auto& a : g->actions) {
    if (a.time_ms > 30000 || a.targets.size() != g->servos.size()) std::abort();
    for (const auto& t : a.targets)
      if (t.position && *t.position > 1000) std::abort();
  }
  auto again = parse_action_group(format_action_group(*g));
  if (!again.ok() || !(*again == *g)) std::abort();
  return 0;
}

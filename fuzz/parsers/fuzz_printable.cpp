// printable() (core/printable.hpp) on arbitrary bytes: what it returns holds no byte below
// 0x20, no 0x7f and no C1 control, is valid UTF-8, and passing it through again changes
// nothing (messages may be escaped where made and again where printed).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/printable.hpp"

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_printable: %s\n", what);
  std::abort();
}

// Valid UTF-8 with no C0/C1 controls; a plain decoder, independent of printable's own.
bool clean_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto b = static_cast<std::uint8_t>(s[i]);
    if (b < 0x20 || b == 0x7f) return false;
    if (b < 0x80) {
      ++i;
      continue;
    }
    const std::size_t n = b >= 0xF0 ? 4 : b >= 0xE0 ? 3 : b >= 0xC2 ? 2 : 0;
    if (n == 0 || b > 0xF4 || i + n > s.size()) return false;
    std::uint32_t code = b & (0x7Fu >> n);
    for (std::size_t k = 1; k < n; ++k) {
      const auto c = static_cast<std::uint8_t>(s[i + k]);
      if ((c & 0xC0u) != 0x80u) return false;
      code = (code << 6) | (c & 0x3Fu);
    }
    if ((n == 3 && code < 0x800) || (n == 4 && code < 0x10000) || (code >= 0xD800 && code <= 0xDFFF) ||
        code > 0x10FFFF || (code >= 0x80 && code <= 0x9F))
      return false;
    i += n;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string once = armctl::printable(text);
  check(clean_utf8(once), "output holds a control character or invalid UTF-8");
  check(armctl::printable(once) == once, "a second pass changed the text");
  check(once.size() <= 4 * size, "output more than 4 bytes per input byte");
  return 0;
}

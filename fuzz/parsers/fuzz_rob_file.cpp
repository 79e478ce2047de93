// Arbitrary bytes into the .rob reader (files/rob_file.hpp): never a crash; every error
// names the source and an offset; anything accepted holds servos 1..6 with every position
// in 0..1000, and exports back to the very same bytes but for the unknown header bytes 8..15.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "files/rob_file.hpp"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_rob_file: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl::files;
  const std::vector<std::uint8_t> bytes(data, data + size);
  auto g = parse_rob_file(bytes, "fuzz");
  if (!g) {
    check(g.error().message.rfind("fuzz: offset ", 0) == 0, "an error that does not name the file and offset");
    check(g.error().kind == armctl::ErrorKind::invalid_config, "an error of another kind");
    return 0;
  }
  check(g->servos == std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6}, "servos other than 1..6");
  for (const auto& a : g->actions)
    for (const auto& t : a.targets) check(t.position && *t.position <= 1000, "a position outside 0..1000");
  auto out = format_rob_file(*g);
  check(out.ok(), "an accepted file does not export");
  check(out->size() == bytes.size(), "the export has another size");
  for (std::size_t i = 0; i < bytes.size(); ++i)
    if (i < 8 || i >= kRobHeaderBytes) check((*out)[i] == bytes[i], "the export changed a byte");
  return 0;
}

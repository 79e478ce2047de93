// Arbitrary text into the recording parser (motion/recording.hpp): never a crash; every
// error names the source and is invalid_config; anything accepted has increasing times,
// one finite value per joint, and survives a format/parse round trip.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "files/recording_file.hpp"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_recording: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl::motion;
  using namespace armctl::files;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto r = parse_recording(text, "fuzz");
  if (!r) {
    check(r.error().message.rfind("fuzz:", 0) == 0, "an error that does not name the file");
    check(r.error().kind == armctl::ErrorKind::invalid_config, "an error of another kind");
    return 0;
  }
  check(!r->samples.empty() && !r->joints.empty(), "accepted without samples or joints");
  for (std::size_t i = 0; i < r->samples.size(); ++i) {
    check(r->samples[i].positions.size() == r->joints.size(), "a sample without one value per joint");
    check(i == 0 || r->samples[i].time > r->samples[i - 1].time, "times not increasing");
    for (double v : r->samples[i].positions) check(std::isfinite(v), "a non-finite value");
  }
  auto again = parse_recording(format_recording(*r), "again");
  check(again.ok(), "the formatted recording does not parse");
  check(again->samples.size() == r->samples.size() && again->joints == r->joints && again->arm == r->arm,
        "the round trip changed the recording");
  for (std::size_t i = 0; i < r->samples.size(); ++i)
    for (std::size_t j = 0; j < r->joints.size(); ++j) {
      const double a = r->samples[i].positions[j], b = again->samples[i].positions[j];
      check(std::abs(a - b) <= 1e-12 * std::max(1.0, std::abs(a)), "the round trip changed a value");
    }
  return 0;
}

// Arbitrary text into the points-file parser (files/points_file.hpp): never a crash;
// every error names the source and is invalid_config; anything accepted has valid unique
// names and finite values, and survives a format/parse round trip.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "files/points_file.hpp"

namespace {

using namespace armctl::files;

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_points_file: %s\n", what);
    std::abort();
  }
}

bool close(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(1.0, std::abs(a)); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto f = parse_points_file(text, "fuzz");
  if (!f) {
    check(f.error().message.rfind("fuzz:", 0) == 0, "an error that does not name the file");
    check(f.error().kind == armctl::ErrorKind::invalid_config, "an error of another kind");
    return 0;
  }
  for (std::size_t i = 0; i < f->points.size(); ++i) {
    const Point& p = f->points[i];
    check(!bad_name(p.name), "an accepted bad name");
    check(f->find(p.name) == &p, "a name twice");
    check(p.position.allFinite(), "a non-finite position");
    for (const auto& j : p.joints) check(std::isfinite(j.value), "a non-finite joint value");
  }
  auto again = parse_points_file(format_points_file(*f), "again");
  check(again.ok(), "the formatted file does not parse");
  check(again->points.size() == f->points.size(), "the round trip changed the point count");
  for (std::size_t i = 0; i < f->points.size(); ++i) {
    const Point &a = f->points[i], &b = again->points[i];
    check(a.name == b.name && a.joints.size() == b.joints.size() && a.elbow == b.elbow, "the round trip changed a point");
    for (std::size_t k = 0; k < a.joints.size(); ++k)
      check(close(a.joints[k].value, b.joints[k].value) && a.joints[k].dimension == b.joints[k].dimension,
            "the round trip changed a joint value");
    for (int k = 0; k < 3; ++k) check(close(a.position[k], b.position[k]), "the round trip changed a position");
    check(a.roll.has_value() == b.roll.has_value() && (!a.roll || close(*a.roll, *b.roll)), "the round trip changed roll");
    check(a.pitch.has_value() == b.pitch.has_value() && (!a.pitch || close(*a.pitch, *b.pitch)), "the round trip changed pitch");
    check(a.yaw.has_value() == b.yaw.has_value() && (!a.yaw || close(*a.yaw, *b.yaw)), "the round trip changed yaw");
  }
  return 0;
}

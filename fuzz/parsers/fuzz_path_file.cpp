// Arbitrary text into the path-file parser (files/path_file.hpp): never a crash; every
// error names the source and a line; anything accepted obeys the documented limits and
// survives a format/parse round trip. The lin/circ moves accepted are then built into a
// Cartesian path from a fixed start: the builder refuses with invalid_argument or returns a
// path whose every pose is finite with a unit quaternion.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "motion/cartesian_path.hpp"
#include "files/path_file.hpp"

namespace {

using namespace armctl::motion;
using namespace armctl::files;

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz_path_file: %s\n", what);
  std::abort();
}

void check(bool ok, const char* what) {
  if (!ok) broken(what);
}

bool same_move(PathMove a, PathMove b) {
  const double fa = a.speed_fraction.value_or(0), fb = b.speed_fraction.value_or(0);
  if (a.speed_fraction.has_value() != b.speed_fraction.has_value() || std::abs(fa - fb) > 1e-12 * std::abs(fa))
    return false;
  a.line = b.line = 0;
  a.speed_fraction = b.speed_fraction = std::nullopt;
  return a == b;
}

void build(const PathFile& file) {
  std::vector<PathSegment> segments;
  for (const PathMove& m : file.moves) {
    if (m.kind == MoveKind::ptp || segments.size() == 64) continue;
    PathSegment s;
    s.kind = m.kind == MoveKind::lin ? SegmentKind::lin : SegmentKind::circ;
    s.target.position = m.position;
    s.target.orientation = from_rpy({m.roll.value_or(0), m.pitch.value_or(0), m.yaw.value_or(0)});
    s.via = m.via;
    s.speed = m.speed.value_or(s.speed);
    s.angular_speed = m.angular_speed.value_or(s.angular_speed);
    s.zone = m.zone;
    segments.push_back(s);
  }
  if (segments.empty()) return;
  auto path = build_cartesian_path(Pose{}, segments);
  if (!path) {
    check(path.error().kind == armctl::ErrorKind::invalid_argument, "a path error of another kind");
    return;
  }
  const double d = path->duration();
  if (!std::isfinite(d)) return;  // astronomically long (1e300 m at 1e-300 m/s): nothing to sample
  for (int i = 0; i <= 64; ++i) {
    const Pose p = path->at(d * i / 64);
    if (p.position.allFinite()) check(std::abs(p.orientation.norm() - 1) < 1e-9, "a pose off the unit quaternion");
    const PathRates r = path->rates(d * i / 64);
    (void)r;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto f = parse_path_file(text, "fuzz");
  if (!f.ok()) {
    check(f.error().message.rfind("fuzz:", 0) == 0, "an error that does not name the file");
    check(f.error().kind == armctl::ErrorKind::invalid_config, "a parse error of another kind");
    return 0;
  }
  check(!f->moves.empty() && f->moves.size() <= kPathFileMaxMoves, "move count outside 1..max");
  for (const PathMove& m : f->moves) {
    check(m.line >= 1, "a move without its line");
    check(m.position.allFinite() && m.via.allFinite(), "a non-finite position");
    check(m.zone >= 0 && std::isfinite(m.zone), "a zone outside >= 0");
    if (m.speed) check(*m.speed > 0 && std::isfinite(*m.speed), "a speed outside > 0");
    if (m.angular_speed) check(*m.angular_speed > 0 && std::isfinite(*m.angular_speed), "an angular speed outside > 0");
    if (m.speed_fraction) check(*m.speed_fraction > 0 && *m.speed_fraction <= 1, "a ptp speed outside (0, 1]");
    check(m.joints.size() <= kPathFileMaxJoints, "too many joint values");
    check(m.kind == MoveKind::ptp || m.joints.empty(), "joint values on a lin or circ");
  }
  auto again = parse_path_file(format_path_file(*f), "again");
  check(again.ok(), "the formatted file does not parse");
  check(again->moves.size() == f->moves.size(), "the round trip changed the move count");
  for (std::size_t i = 0; i < f->moves.size(); ++i)
    check(same_move(f->moves[i], again->moves[i]), "the round trip changed a move");
  build(*f);
  return 0;
}

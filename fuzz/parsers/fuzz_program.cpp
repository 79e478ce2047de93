// Arbitrary text into the program parser and flow (program/program_parser.hpp,
// program_flow.hpp): never a crash or a hang; every parse error names the source with a
// line and column, and is invalid_config; a program that parses runs its flow (with small
// caps, so that loops end quickly) to a flow or to an error that names the source.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "program/program_flow.hpp"
#include "program/program_parser.hpp"

namespace {

using namespace armctl::program;
using namespace armctl::files;

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_program: %s\n", what);
    std::abort();
  }
}

bool names_place(const std::string& m) {
  // "fuzz:LINE:COLUMN: " or "fuzz: " (the whole file)
  return m.rfind("fuzz:", 0) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto program = parse_program(text, "fuzz");
  if (!program) {
    check(names_place(program.error().message), "a parse error that does not name the file");
    check(program.error().kind == armctl::ErrorKind::invalid_config, "a parse error of another kind");
    return 0;
  }
  static const PointsFile points =
      parse_points_file("p x=200mm y=0mm z=50mm\nq joints=0deg,10deg\nhome joints=0deg\n", "points").value();
  FlowLimits limits;
  limits.loop_iterations = 50;
  limits.statements = 20'000;
  limits.actions = 500;
  auto flow = run_flow(*program, points, limits);
  if (!flow) {
    check(names_place(flow.error().message), "a flow error that does not name the file");
    return 0;
  }
  check(flow->actions.size() <= limits.actions, "more actions than the cap");
  for (const auto& a : flow->actions) {
    check(a.at.line >= 1 && a.at.column >= 1, "an action without its place");
    if (a.kind == ActionKind::wait) check(a.seconds >= 0 && a.seconds <= 3600, "a wait outside 0..3600 s");
    if (a.kind == ActionKind::gripper) check(a.closed_fraction >= 0 && a.closed_fraction <= 1, "a gripper outside 0..1");
    if (a.kind == ActionKind::move) {
      check(a.move.override_fraction > 0 && a.move.override_fraction <= 1, "an override outside (0, 1]");
      check(a.move.zone >= 0, "a negative zone");
      if (a.move.speed) check(*a.move.speed > 0, "a speed not above 0");
    }
  }
  return 0;
}

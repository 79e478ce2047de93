// --trace FILE of `armctl arm path` and `armctl program run` (the CSV make demo draws its
// picture from), end to end on the embedded simulated xArm: the plan's rows end where the
// path file says, the positions read back lie near them, and a file that cannot be written
// is refused before anything moves.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "run_armctl.hpp"

namespace {

using armctl::cli_test::contains;
using armctl::cli_test::run_armctl;

constexpr const char* kHeader =
    "kind,line,t_s,planned_x_mm,planned_y_mm,planned_z_mm,measured_x_mm,measured_y_mm,measured_z_mm";

struct Row {
  std::string kind;
  int line = 0;
  double t = 0;
  double planned[3] = {0, 0, 0};
  double measured[3] = {NAN, NAN, NAN};
};

// The rows of a trace; fails the test on a wrong header or a row that is not 9 fields.
std::vector<Row> read_trace(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, kHeader);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f(1);  // split at every comma: a plan row ends in three empty fields
    for (char c : line) {
      if (c == ',') f.emplace_back();
      else f.back() += c;
    }
    EXPECT_EQ(f.size(), 9u) << line;
    if (f.size() != 9) continue;
    Row r;
    r.kind = f[0];
    r.line = std::stoi(f[1]);
    r.t = std::stod(f[2]);
    for (int i = 0; i < 3; ++i) r.planned[i] = std::stod(f[3 + std::size_t(i)]);
    if (r.kind == "read")
      for (int i = 0; i < 3; ++i) r.measured[i] = std::stod(f[6 + std::size_t(i)]);
    else
      EXPECT_TRUE(f[6].empty() && f[7].empty() && f[8].empty()) << line;
    rows.push_back(r);
  }
  return rows;
}

double distance(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

class TraceCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = std::filesystem::temp_directory_path() /
          ("armctl-trace-cli-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "-" +
           std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    ::setenv("ARMCTL_STATE_DIR", dir.c_str(), 1);
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::filesystem::path dir;
};

// The example square: a PTP (line 5) to its first corner, then four blended LINs (line 6 on)
// at z = 100 mm. The plan ends at the last corner, the reads on the LINs follow the plan
// within the xArm's quantization (twice a LIN's limit, 3.27 mm: docs/benchmarks.md), the
// plan's time goes forward.
TEST_F(TraceCli, PathTraceHasThePlanAndTheReadBacks) {
  const std::string square = std::string(ARMCTL_SOURCE_DIR) + "/examples/paths/xarm-square.path";
  const auto csv = dir / "square.csv";
  auto r = run_armctl("arm path " + square + " --trace " + csv.string(), "2>&1");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto rows = read_trace(csv);
  std::size_t plans = 0, reads = 0;
  double last_t = -1;
  const Row* last_plan = nullptr;
  for (const Row& row : rows) {
    EXPECT_TRUE(row.line == 5 || row.line == 6) << row.line;
    if (row.kind == "plan") {
      ++plans;
      EXPECT_GE(row.t, last_t);
      last_t = row.t;
      last_plan = &row;
      if (row.line == 6) {
        EXPECT_NEAR(row.planned[2], 100.0, 0.5) << "the square is flat";
      }
    } else {
      ASSERT_EQ(row.kind, "read");
      ++reads;
      // The LINs only: the PTP from the stretched-out start lags its plan by up to 9 mm at
      // the tool, as the CLI's own "tool within .. mm of the plan" says.
      if (row.line == 6) {
        EXPECT_LT(distance(row.planned, row.measured), 3.27) << "at t=" << row.t;
      }
    }
  }
  EXPECT_GT(plans, 400u) << "11 s of plan every 20 ms";
  EXPECT_GT(reads, 20u);
  ASSERT_NE(last_plan, nullptr);
  const double corner[3] = {180, -40, 100};
  EXPECT_LT(distance(last_plan->planned, corner), 0.5);
}

// A program's trace: each motion piece under the line it starts at, a LIN's plan along its
// line from point a to point b.
TEST_F(TraceCli, ProgramTraceFollowsTheProgramsMoves) {
  std::ofstream(dir / "short.prog") << "ptp a speed=50%\nlin b speed=60mm/s\nwait 0.1s\n";
  std::ofstream(dir / "short.points")
      << "a x=180mm y=-30mm z=100mm pitch=50deg\nb x=180mm y=30mm z=100mm pitch=50deg\n";
  const auto csv = dir / "short.csv";
  auto r = run_armctl("program run " + (dir / "short.prog").string() + " --points " + (dir / "short.points").string() +
                          " --trace " + csv.string(),
                      "2>&1");
  ASSERT_EQ(r.status, 0) << r.out;
  std::vector<const Row*> lin;
  const auto rows = read_trace(csv);
  for (const Row& row : rows) {
    EXPECT_TRUE(row.line == 1 || row.line == 2) << row.line;
    if (row.kind == "plan" && row.line == 2) lin.push_back(&row);
  }
  ASSERT_GT(lin.size(), 10u);
  const double a[3] = {180, -30, 100}, b[3] = {180, 30, 100};
  EXPECT_LT(distance(lin.front()->planned, a), 0.5);
  EXPECT_LT(distance(lin.back()->planned, b), 0.5);
  for (const Row* row : lin) {
    EXPECT_NEAR(row->planned[0], 180.0, 0.5);
    EXPECT_NEAR(row->planned[2], 100.0, 0.5);
  }
}

// A trace file that cannot be written is an error naming it, and nothing moves (no
// "planned" line); an empty name is a usage error.
TEST_F(TraceCli, AnUnwritableTraceIsRefusedBeforeAnythingMoves) {
  const std::string square = std::string(ARMCTL_SOURCE_DIR) + "/examples/paths/xarm-square.path";
  const std::string prog = std::string(ARMCTL_SOURCE_DIR) + "/examples/programs/xarm-pick-place.prog";
  const std::string bad = (dir / "no-such-folder" / "t.csv").string();
  for (const std::string& cmd : {"arm path " + square, "program run " + prog}) {
    auto r = run_armctl(cmd + " --trace " + bad, "2>&1");
    EXPECT_EQ(r.status, 1) << cmd << ": " << r.out;
    EXPECT_TRUE(contains(r.out, "armctl: I/O error: --trace " + bad + ": cannot write it: No such file or directory"))
        << r.out;
    EXPECT_FALSE(contains(r.out, "planned")) << "nothing moved: " << r.out;
    auto empty = run_armctl(cmd + " --trace ''", "2>&1");
    EXPECT_NE(empty.status, 0) << empty.out;  // CLI11's status for a value its check refused
    EXPECT_TRUE(contains(empty.out, "a file name is needed")) << empty.out;
  }
}

}  // namespace

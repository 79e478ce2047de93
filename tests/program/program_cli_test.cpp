// armctl program end to end (runs build/armctl) on the embedded simulated arms: check,
// run --dry-run --json, a refused program (exit 1, the line named, nothing run), and the
// usage errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli/run_armctl.hpp"

namespace armctl::cli_test {
namespace {

std::string example(const std::string& name) { return std::string(ARMCTL_SOURCE_DIR) + "/examples/programs/" + name; }

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("armctl-program-" + std::to_string(::getpid()) + "-" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(ProgramCli, ChecksBothExamples) {
  for (const std::string arm : {"xarm", "scara"}) {
    const auto r = run_armctl("program check " + example(arm + "-pick-place.prog") + " --arm " + arm);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_TRUE(contains(r.out, ": OK on arm '" + arm + "'")) << r.out;
    EXPECT_TRUE(contains(r.out, "estimated run time")) << r.out;
  }
}

TEST(ProgramCli, DryRunPrintsEveryLineAsJson) {
  const std::string prog = write_temp("short.prog", "ptp a speed=50%\nlin b speed=60mm/s\nprint \"at b\"\nwait 0.1s\n");
  const std::string points = write_temp("short.points", "a x=180mm y=-30mm z=100mm pitch=50deg\nb x=180mm y=30mm z=100mm pitch=50deg\n");
  const auto r = run_armctl("program run " + prog + " --points " + points + " --dry-run --json", "2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.out;
  std::istringstream lines(r.out);
  std::vector<std::string> events;
  for (std::string line; std::getline(lines, line);) events.push_back(nlohmann::json::parse(line).at("event"));
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front(), "planned");
  EXPECT_EQ(events.back(), "finished");
  EXPECT_EQ(std::count(events.begin(), events.end(), "line"), 3);  // ptp, lin, wait
  EXPECT_EQ(std::count(events.begin(), events.end(), "print"), 1);
  std::filesystem::remove(prog);
  std::filesystem::remove(points);
}

// The estimate printed before a run is at the run's --override (motions 1/override as long,
// WAITs as written); it said 81.8 s for a run of 164.4 s at 50 %.
TEST(ProgramCli, TheEstimateIsAtTheOverride) {
  const std::string prog = write_temp("slow.prog", "ptp a speed=50%\nlin b speed=60mm/s\nwait 0.1s\n");
  const std::string points = write_temp("slow.points", "a x=180mm y=-30mm z=100mm pitch=50deg\nb x=180mm y=30mm z=100mm pitch=50deg\n");
  auto planned = [&](const std::string& override) {
    const auto r = run_armctl("program run " + prog + " --points " + points + " --dry-run --json" + override, "2>/dev/null");
    EXPECT_EQ(r.status, 0) << r.out;
    std::istringstream lines(r.out);
    std::string first;
    std::getline(lines, first);
    const auto event = nlohmann::json::parse(first);
    EXPECT_EQ(event.at("event"), "planned");
    return event.at("duration_s").get<double>();
  };
  const double full = planned(""), half = planned(" --override 50%");
  // Motions twice as long, the 0.1 s WAIT the same.
  EXPECT_NEAR(half, 2 * full - 0.1, 1e-6) << full << " " << half;
  std::filesystem::remove(prog);
  std::filesystem::remove(points);
}

TEST(ProgramCli, RefusesAProgramThatFailsTheCheck) {
  const std::string prog = write_temp("far.prog", "print \"start\"\nptp near\nlin far\n");
  const std::string points = write_temp("far.points", "near x=180mm y=0mm z=100mm pitch=50deg\nfar x=600mm y=0mm z=100mm pitch=50deg\n");
  const auto r = run_armctl("program run " + prog + " --points " + points + " --dry-run");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(contains(r.out, prog + ":3: (LIN far): ")) << r.out;
  EXPECT_FALSE(contains(r.out, "start")) << r.out;  // nothing ran, not even the PRINT
  const auto parse = run_armctl("program check " + prog + " --points " + write_temp("bad.points", "near\n"));
  EXPECT_EQ(parse.status, 1);
  EXPECT_TRUE(contains(parse.out, "bad.points:1:5: found '', expected the point's position")) << parse.out;
  std::filesystem::remove(prog);
  std::filesystem::remove(points);
}

TEST(ProgramCli, UsageErrors) {
  const std::string prog = example("xarm-pick-place.prog");
  auto r = run_armctl("program run " + prog + " --override 0%");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.out, "--override (of the programmed speeds): '0%' is too small; allowed 0.1..100 %")) << r.out;
  // An override without its unit, or of 1e-300 %, was accepted.
  r = run_armctl("program run " + prog + " --override 50");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.out, "--override (of the programmed speeds): '50' has no unit; write a percentage like 50%"))
      << r.out;
  r = run_armctl("program run " + prog + " --override 1e-300%");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.out, "'1e-300%' is too small; allowed 0.1..100 %")) << r.out;
  r = run_armctl("program run " + prog + " --dry-run --device hid");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.out, "--dry-run runs on the embedded simulated arm")) << r.out;
  r = run_armctl("program compile " + example("scara-pick-place.prog") + " --arm scara --group 1");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.out, "action groups need a Robot Commands board")) << r.out;
  r = run_armctl("program compile " + prog + " --group 300");
  EXPECT_NE(r.status, 0);
  r = run_armctl("program frobnicate");
  EXPECT_NE(r.status, 0);
  EXPECT_TRUE(contains(r.out, "allowed: check, run, compile")) << r.out;
}

TEST(ProgramCli, CompilesTheXarmExampleToAGroup) {
  const auto r = run_armctl("program compile " + example("xarm-pick-place.prog") + " --group 4 --json", "2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("group"), 4);
  EXPECT_GT(j.at("actions").get<int>(), 10);
  EXPECT_LE(j.at("sampling_error_mm").get<double>(), 1.0);
}

}  // namespace
}  // namespace armctl::cli_test

// Mis-assembled simulators from the command line (docs/simulator.md "Mis-assembled
// simulators"): `--device 'sim?miscal=SEED'` opens them, their truth reaches only the debug
// log (ARMCTL_DEBUG), and bad seeds are refused naming the key, the value and what is allowed.
#include <gtest/gtest.h>

#include <string>

#include "run_armctl.hpp"

namespace {

using armctl::cli_test::contains;
using armctl::cli_test::run_armctl;

TEST(MiscalCli, TheTruthIsOnlyInTheDebugLog) {
  const auto quiet = run_armctl("bus --device 'sim?miscal=7' position all", "2>&1");
  EXPECT_EQ(quiet.status, 0) << quiet.out;
  EXPECT_FALSE(contains(quiet.out, "miscal")) << quiet.out;
  EXPECT_FALSE(contains(quiet.out, "zero +")) << quiet.out;
  const std::string with_debug = std::string("ARMCTL_DEBUG=1 ") + ARMCTL_BINARY_DIR + "/armctl";
  FILE* p = ::popen((with_debug + " bus --device 'sim?miscal=7' position all 2>&1 >/dev/null").c_str(), "r");
  std::string err;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) err.append(buf, n);
  EXPECT_EQ(::pclose(p), 0) << err;
  EXPECT_TRUE(contains(err, "armctl: debug: embedded simulated arm: miscal 7 (scara): joint 1 zero +470")) << err;
}

TEST(MiscalCli, BadSeedsAreRefusedNamingTheKey) {
  const auto bus = run_armctl("bus --device 'sim?miscal=seven' position all");
  EXPECT_NE(bus.status, 0);
  EXPECT_TRUE(contains(bus.out, "miscal 'seven' is not a seed (allowed: a whole number 0..4294967295)")) << bus.out;
  const auto xarm = run_armctl("xarm --device 'sim?miscal=-1' positions");
  EXPECT_NE(xarm.status, 0);
  EXPECT_TRUE(contains(xarm.out, "miscal '-1' is not a seed")) << xarm.out;
  const auto sim = run_armctl("sim xarm --miscal 1e3");
  EXPECT_NE(sim.status, 0);
  EXPECT_TRUE(contains(sim.out, "--miscal '1e3' is not a seed (allowed: a whole number 0..4294967295)")) << sim.out;
  const auto scara = run_armctl("sim scara --miscal x --listen /nonexistent/dir/s.sock");
  EXPECT_NE(scara.status, 0);
  EXPECT_TRUE(contains(scara.out, "--miscal 'x' is not a seed")) << scara.out;
}

TEST(MiscalCli, TheMisassembledXarmShowsItsDuplicateIdAsNoAnswer) {
  // Seed 7: the servo in place 5 answers ID 2, so nobody answers 5: a read of the arm fails.
  const auto r = run_armctl("xarm --device 'sim?miscal=7' positions");
  EXPECT_NE(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "no ServoPositionRead reply")) << r.out;
  // The servos that answer alone read as usual.
  const auto some = run_armctl("xarm --device 'sim?miscal=7' positions 3 4");
  EXPECT_EQ(some.status, 0) << some.out;
  EXPECT_TRUE(contains(some.out, "servo 3:  500")) << some.out;
}

}  // namespace

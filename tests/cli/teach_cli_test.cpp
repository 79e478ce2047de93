// armctl teach / replay / xarm group import|export end to end on the embedded simulated arms,
// driven from a script on standard input (no terminal).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "run_armctl.hpp"

namespace armctl::cli_test {
namespace {

std::string dir() { return ::testing::TempDir(); }
std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(TeachCli, PointsFromAScript) {
  const std::string points = dir() + "/cli.points";
  std::remove(points.c_str());
  auto r = run_armctl("teach --points " + points + " <<'EOF'\nhome\n\nlin\nhome\nEOF\n");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "recorded home:")) << r.out;
  EXPECT_TRUE(contains(r.out, "recorded p1:")) << r.out;
  EXPECT_TRUE(contains(r.out, "not recorded: 'lin'")) << r.out;
  EXPECT_TRUE(contains(r.out, "replaced home:")) << r.out;
  EXPECT_TRUE(contains(r.out, "torque on, holding; 3 points recorded")) << r.out;
  const std::string text = slurp(points);
  EXPECT_TRUE(contains(text, "home joints=0deg,0deg,0deg,0deg,0deg,0deg")) << text;
  EXPECT_TRUE(contains(text, "p1   joints=")) << text;
}

TEST(TeachCli, RecordThenReplayOnBothArms) {
  for (const std::string arm : {"xarm", "scara"}) {
    const std::string rec = dir() + "/cli-" + arm + ".rec";
    // The embedded SCARA's joint bus (9600 baud) reads its seven joints at about 17 Hz.
    const std::string rate = arm == "scara" ? "10Hz" : "20Hz";
    auto r = run_armctl("teach --arm " + arm + " --record " + rate + " --out " + rec + " --duration 1s </dev/null");
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_TRUE(contains(r.out, "samples over")) << r.out;
    EXPECT_TRUE(contains(slurp(rec), "arm " + arm + "\nrate " + rate + "\n")) << slurp(rec);
    auto p = run_armctl("replay " + rec + " --speed 50%");
    ASSERT_EQ(p.status, 0) << p.out;
    EXPECT_TRUE(contains(p.out, "replay through")) << p.out;
  }
}

// Under --json, teach and replay say every event as one JSON object per line.
TEST(TeachCli, TeachAndReplayAsJsonLines) {
  const std::string points = dir() + "/cli-json.points";
  std::remove(points.c_str());
  auto r = run_armctl("teach --json --points " + points + " <<'EOF'\nhome\nlin\nEOF\n", "2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.out;
  auto docs = json_lines(r.out);
  ASSERT_EQ(docs.size(), 4u) << r.out;
  EXPECT_EQ(docs[0]["event"], "started");
  EXPECT_EQ(docs[1]["event"], "recorded");
  EXPECT_EQ(docs[1]["point"], "home");
  ASSERT_EQ(docs[1]["joints"].size(), 6u) << r.out;
  EXPECT_EQ(docs[1]["joints"][0]["unit"], "rad");
  EXPECT_EQ(docs[2]["event"], "refused");
  EXPECT_EQ(docs[2]["point"], "lin");
  EXPECT_EQ(docs[3]["event"], "finished");
  EXPECT_EQ(docs[3]["points"], 1);

  const std::string rec = dir() + "/cli-json.rec";
  r = run_armctl("teach --json --record 20Hz --out " + rec + " --duration 1s </dev/null", "2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.out;
  docs = json_lines(r.out);
  ASSERT_EQ(docs.size(), 2u) << r.out;
  EXPECT_EQ(docs[0]["event"], "started");
  EXPECT_EQ(docs[0]["rate_hz"], 20);
  EXPECT_EQ(docs[1]["event"], "finished");
  EXPECT_EQ(docs[1]["samples"], 21) << r.out;  // 0 s .. 1 s at 20 Hz
  EXPECT_EQ(docs[1]["file"], rec);

  r = run_armctl("replay --json " + rec, "2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.out;
  docs = json_lines(r.out);
  ASSERT_GE(docs.size(), 2u) << r.out;
  EXPECT_EQ(docs[0]["event"], "planned");
  EXPECT_EQ(docs[0]["samples"], 21);
  EXPECT_EQ(docs[0]["speed_percent"], 100);
  for (std::size_t i = 1; i < docs.size(); ++i) EXPECT_EQ(docs[i]["event"], "done") << r.out;
}

// A motion made by hand cannot be made again: an --out that cannot be written (no such
// directory, a read-only file) is refused before torque goes off, and nothing is written.
TEST(TeachCli, RecordRefusesAnOutputItCannotWriteBeforeTorqueOff) {
  const std::string missing = dir() + "/nodir/x.rec";
  std::filesystem::remove_all(dir() + "/nodir");
  auto r = run_armctl("teach --record 20Hz --out " + missing + " --duration 1s </dev/null");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "armctl: I/O error: cannot write " + missing + ": directory " + dir() +
                                  "/nodir does not exist; nothing recorded, torque not switched off"))
      << r.out;
  EXPECT_FALSE(contains(r.out, "torque off")) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir() + "/nodir"));

  const std::string readonly = dir() + "/cli-readonly.rec";
  std::filesystem::remove(readonly);
  std::ofstream(readonly) << "mine\n";
  std::filesystem::permissions(readonly, std::filesystem::perms::owner_read);
  r = run_armctl("teach --record 20Hz --out " + readonly + " --duration 1s </dev/null");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "cannot write " + readonly + ": it is read-only (mode 0400)")) << r.out;
  EXPECT_FALSE(contains(r.out, "torque off")) << r.out;
  EXPECT_EQ(slurp(readonly), "mine\n");
}

// Teaching into a file a person wrote keeps their comments; a byte-order mark is no error.
TEST(TeachCli, PointsKeepTheFilesCommentsAndByteOrderMark) {
  const std::string points = dir() + "/cli-kept.points";
  std::ofstream(points, std::ios::binary) << "\xEF\xBB\xBF# my cell\nhome joints=10deg  # safe\n";
  auto r = run_armctl("teach --points " + points + " <<'EOF'\npick\nEOF\n");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(slurp(points), "\xEF\xBB\xBF# my cell\nhome joints=10deg  # safe\npick joints=0deg,0deg,0deg,0deg,0deg,0deg\n");
}

TEST(TeachCli, RefusesBadArgumentsAndRecordings) {
  EXPECT_TRUE(contains(run_armctl("teach").out, "teach needs either --points FILE"));
  EXPECT_TRUE(contains(run_armctl("teach --record 0Hz --out x.rec").out, "allowed is 1..1000 Hz"));
  EXPECT_TRUE(contains(run_armctl("teach --record 20Hz").out, "--record needs --out FILE"));
  const std::string rec = dir() + "/cli-other.rec";
  {
    std::ofstream out(rec);
    out << "arm scara\nrate 20Hz\njoints Z:mm\n0 10\n";
  }
  auto r = run_armctl("replay " + rec + " --arm xarm");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.out, "the recording is of arm 'scara', this arm is 'xarm'")) << r.out;
  EXPECT_TRUE(contains(run_armctl("replay " + rec + " --speed 0%").out,
                       "--speed (of the velocity limits): '0%' is too small; allowed 0.1..100 %"));
  // One percentage parser in every command: a bare number is refused (half, or 0.5 %?).
  EXPECT_TRUE(contains(run_armctl("replay " + rec + " --speed 50").out, "'50' has no unit; write a percentage like 50%"));
}

TEST(TeachCli, ARecordingRateTheLinkCannotKeepIsRefusedBeforeTorqueOff) {
  const std::string rec = dir() + "/too-fast.rec";
  auto r = run_armctl("teach --arm scara --record 20Hz --out " + rec + " --duration 1s </dev/null");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(contains(r.out, "rate 20 Hz is faster than this link allows")) << r.out;
  EXPECT_FALSE(contains(r.out, "torque off")) << r.out;
  EXPECT_FALSE(std::filesystem::exists(rec));
}

TEST(TeachCli, RobImportExport) {
  const std::string grp = dir() + "/cli.grp", rob = dir() + "/cli.rob", back = dir() + "/cli-back.grp";
  {
    std::ofstream out(grp);
    out << "servos 6\n1000 1=500 2=300 3=700 4=0 5=1000 6=258\n20 1=1 2=2 3=3 4=4 5=5 6=6\n";
  }
  auto e = run_armctl("xarm group export " + grp + " --out " + rob);
  ASSERT_EQ(e.status, 0) << e.out;
  EXPECT_EQ(slurp(rob).size(), 16u + 2 * 14);
  auto i = run_armctl("xarm group import " + rob + " --out " + back);
  ASSERT_EQ(i.status, 0) << i.out;
  EXPECT_TRUE(contains(slurp(back), "1000 1=500 2=300 3=700 4=0 5=1000 6=258\n20 1=1 2=2 3=3 4=4 5=5 6=6\n")) << slurp(back);
  auto d = run_armctl("xarm group import " + rob + " --group 2");
  ASSERT_EQ(d.status, 0) << d.out;
  EXPECT_TRUE(contains(d.out, "group 2: 2 actions downloaded")) << d.out;
  auto bad = run_armctl("xarm group import " + grp);
  EXPECT_EQ(bad.status, 1);
  EXPECT_TRUE(contains(bad.out, "offset 0: found bytes")) << bad.out;
}

// The README's `group import examples/groups/wave.rob` has a file to import: the shipped
// wave.rob is what armctl's own writer makes of the shipped wave.grp.
TEST(TeachCli, TheShippedRobFileIsTheShippedGroup) {
  const std::string examples = std::string(ARMCTL_SOURCE_DIR) + "/examples/groups";
  const std::string rob = dir() + "/wave.rob";
  auto e = run_armctl("xarm group export " + examples + "/wave.grp --out " + rob);
  ASSERT_EQ(e.status, 0) << e.out;
  EXPECT_EQ(slurp(rob), slurp(examples + "/wave.rob"));
  auto i = run_armctl("xarm group import " + examples + "/wave.rob --out " + dir() + "/wave.grp");
  ASSERT_EQ(i.status, 0) << i.out;
}

}  // namespace
}  // namespace armctl::cli_test

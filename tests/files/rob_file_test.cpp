// .rob files: synthetic files (no public sample with a licence allowing it was found;
// docs/teach.md), round trips both ways, and every malformed file refused with the offset.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "files/action_group_file.hpp"
#include "files/rob_file.hpp"

namespace armctl::files {
namespace {

std::vector<std::uint8_t> header(std::uint16_t frames) {
  std::vector<std::uint8_t> b{'S', 'O', 'B', 'A', 'R', 'M', std::uint8_t(frames & 0xFF), std::uint8_t(frames >> 8)};
  b.resize(kRobHeaderBytes, 0);
  return b;
}

void frame(std::vector<std::uint8_t>& b, std::uint16_t ms, std::vector<std::uint16_t> p) {
  auto put = [&](std::uint16_t v) {
    b.push_back(std::uint8_t(v & 0xFF));
    b.push_back(std::uint8_t(v >> 8));
  };
  put(ms);
  for (auto v : p) put(v);
}

ActionGroupFile group_of(std::vector<std::pair<std::uint16_t, std::vector<std::uint16_t>>> actions) {
  ActionGroupFile g;
  g.servos = {1, 2, 3, 4, 5, 6};
  for (auto& [ms, p] : actions) {
    rc::GroupAction a;
    a.time_ms = ms;
    for (std::size_t i = 0; i < p.size(); ++i) a.targets.push_back({std::uint8_t(i + 1), p[i]});
    g.actions.push_back(a);
  }
  return g;
}

std::string error_of(const std::vector<std::uint8_t>& b) {
  auto r = parse_rob_file(b, "t.rob");
  EXPECT_FALSE(r);
  if (r) return "";
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_config);
  return r.error().message;
}

TEST(RobFile, ReadsFramesLittleEndianServosOneToSix) {
  auto b = header(2);
  frame(b, 1000, {500, 300, 700, 0, 1000, 258});
  frame(b, 20, {1, 2, 3, 4, 5, 6});
  auto g = parse_rob_file(b, "t.rob");
  ASSERT_TRUE(g) << g.error().message;
  EXPECT_EQ(*g, group_of({{1000, {500, 300, 700, 0, 1000, 258}}, {20, {1, 2, 3, 4, 5, 6}}}));
}

TEST(RobFile, RoundTripsBothWays) {
  const auto g = group_of({{0, {0, 0, 0, 0, 0, 0}}, {30000, {1000, 999, 1, 500, 250, 750}}, {800, {12, 34, 56, 78, 90, 100}}});
  auto bytes = format_rob_file(g);
  ASSERT_TRUE(bytes) << bytes.error().message;
  EXPECT_EQ(bytes->size(), kRobHeaderBytes + 3 * kRobFrameBytes);
  EXPECT_EQ(bytes->at(6), 3);
  EXPECT_EQ(bytes->at(7), 0);
  auto back = parse_rob_file(*bytes);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(*back, g);  // import(export(g)) == g
  auto again = format_rob_file(*back);
  ASSERT_TRUE(again);
  EXPECT_EQ(*again, *bytes);  // export(import(b)) == b for a file with a zero header tail
}

TEST(RobFile, ExportListsServosOneToSixWhateverTheGroupOrder) {
  ActionGroupFile g = group_of({{100, {1, 2, 3, 4, 5, 6}}});
  g.servos = {6, 5, 4, 3, 2, 1};
  std::reverse(g.actions[0].targets.begin(), g.actions[0].targets.end());
  auto bytes = format_rob_file(g);
  ASSERT_TRUE(bytes) << bytes.error().message;
  EXPECT_EQ(*parse_rob_file(*bytes), group_of({{100, {1, 2, 3, 4, 5, 6}}}));
}

TEST(RobFile, LargestFile) {
  std::vector<std::pair<std::uint16_t, std::vector<std::uint16_t>>> actions(kRobMaxFrames, {10, {1, 2, 3, 4, 5, 6}});
  auto bytes = format_rob_file(group_of(actions));
  ASSERT_TRUE(bytes);
  EXPECT_EQ(bytes->size(), kRobMaxBytes);
  EXPECT_TRUE(parse_rob_file(*bytes));
}

TEST(RobFile, RefusesMalformedFilesNamingTheOffset) {
  EXPECT_EQ(error_of({}), "t.rob: offset 0: 0 bytes; a .rob file is a 16-byte header ('SOBARM', frame count) then 14-byte frames");
  auto b = header(1);
  frame(b, 100, {1, 2, 3, 4, 5, 6});
  auto bad_magic = b;
  bad_magic[0] = 'X';
  EXPECT_EQ(error_of(bad_magic), "t.rob: offset 0: found bytes 58 4f 42 41 52 4d; a .rob file starts with 'SOBARM' (53 4f 42 41 52 4d)");
  auto zero = b;
  zero[6] = 0;
  EXPECT_EQ(error_of(zero), "t.rob: offset 6: frame count 0 (bytes 00 00); allowed is 1..1020");
  auto many = b;
  many[6] = 0xFD;
  many[7] = 0x03;  // 1021
  EXPECT_EQ(error_of(many), "t.rob: offset 6: frame count 1021 (bytes fd 03); allowed is 1..1020");
  auto short_file = b;
  short_file.pop_back();
  EXPECT_EQ(error_of(short_file), "t.rob: offset 6: frame count 1 needs 30 bytes (16 + 1 x 14); the file has 29 (0 frames and 13 bytes)");
  auto long_file = b;
  frame(long_file, 100, {1, 2, 3, 4, 5, 6});
  EXPECT_EQ(error_of(long_file), "t.rob: offset 6: frame count 1 needs 30 bytes (16 + 1 x 14); the file has 44 (2 frames)");
  auto slow = header(1);
  frame(slow, 30001, {1, 2, 3, 4, 5, 6});
  EXPECT_EQ(error_of(slow), "t.rob: offset 16: frame 1: time 30001 ms; allowed is 0..30000");
  auto far = header(2);
  frame(far, 100, {1, 2, 3, 4, 5, 6});
  frame(far, 100, {1, 2, 1001, 4, 5, 6});
  EXPECT_EQ(error_of(far), "t.rob: offset 36: frame 2: servo 3 position 1001 (bytes e9 03); allowed is 0..1000");
  // Big-endian would read 500 (01 f4) as 0xf401: the check catches a file of the other order.
  auto swapped = header(1);
  swapped.insert(swapped.end(), {0x03, 0xe8, 0x01, 0xf4, 0x01, 0xf4, 0x01, 0xf4, 0x01, 0xf4, 0x01, 0xf4, 0x01, 0xf4});
  EXPECT_EQ(error_of(swapped), "t.rob: offset 16: frame 1: time 59395 ms; allowed is 0..30000");
}

TEST(RobFile, ExportRefusesWhatTheLayoutCannotHold) {
  auto keep = group_of({{100, {1, 2, 3, 4, 5, 6}}});
  keep.actions[0].targets[2].position.reset();
  EXPECT_EQ(format_rob_file(keep).error().message, "action 1: servo 3 is 'keep' or missing; a .rob frame gives every position");
  ActionGroupFile three;
  three.servos = {1, 2, 3};
  three.actions.push_back({100, {{1, 500}, {2, 500}, {3, 500}}});
  EXPECT_EQ(format_rob_file(three).error().message, "the group names servos 1,2,3; a .rob file holds exactly servos 1..6");
  auto slow = group_of({{30001, {1, 2, 3, 4, 5, 6}}});
  EXPECT_EQ(format_rob_file(slow).error().message, "action 1: time 30001 ms; a .rob frame allows 0..30000");
  EXPECT_EQ(format_rob_file(group_of({})).error().message, "the group has 0 actions; a .rob file holds 1..1020");
}

TEST(RobFile, ReadsFilesAndRefusesOthers) {
  const std::string dir = ::testing::TempDir();
  EXPECT_EQ(read_rob_file(dir).error().kind, ErrorKind::io);
  auto bytes = format_rob_file(group_of({{100, {1, 2, 3, 4, 5, 6}}})).value();
  const std::string path = dir + "/teach_test.rob";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
  }
  auto g = read_rob_file(path);
  ASSERT_TRUE(g) << g.error().message;
  EXPECT_EQ(g->actions.size(), 1u);
}

// A group file (what .rob files import to) saved with a UTF-8 byte-order mark reads as
// without it; errors keep their columns.
TEST(RobFile, AGroupFileWithAByteOrderMarkReads) {
  const std::string path = ::testing::TempDir() + "/teach_test_bom.grp";
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBFservos 1\n100 1=500\n";
  auto g = read_action_group_file(path);
  ASSERT_TRUE(g) << g.error().message;
  EXPECT_EQ(g->actions.size(), 1u);
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBF" "100 1=2000\n";
  const std::string plain = parse_action_group("100 1=2000\n", "x").error().message;
  EXPECT_EQ(read_action_group_file(path).error().message, path + plain.substr(1));
  std::remove(path.c_str());
}

}  // namespace
}  // namespace armctl::files

// The action-group text format (files/action_group_file.hpp): good files, and bad files
// whose errors name the line, the field and what is allowed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "files/action_group_file.hpp"

namespace armctl::files {
namespace {

TEST(ActionGroupFile, ParsesTheDocumentedExample) {
  const char* text =
      "# wave: three servos, four actions\n"
      "servos 3\n"
      "1000  1=500 2=300 3=700\n"
      "800ms 1=30deg 2=-15deg 3=500   # degrees from centre\n"
      "\n"
      "500   1=keep 2=500 3=500\r\n"
      "0     3=0 1=1000 2=12.5deg\n";
  auto g = parse_action_group(text, "wave.grp");
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_EQ(g->servos, (std::vector<std::uint8_t>{1, 2, 3}));
  ASSERT_EQ(g->actions.size(), 4u);
  EXPECT_EQ(g->actions[0].time_ms, 1000);
  EXPECT_EQ(g->actions[1].time_ms, 800);
  EXPECT_EQ(g->actions[1].targets[0].position, 625);  // 500 + 30 x 1000/240
  EXPECT_EQ(g->actions[1].targets[1].position, 438);  // 500 - 62.5, rounded away from zero
  EXPECT_FALSE(g->actions[2].targets[0].position.has_value());  // keep
  EXPECT_EQ(g->actions[3].targets[0].servo, 3);
  EXPECT_EQ(g->actions[3].targets[2].position, 552);
}

TEST(ActionGroupFile, FormatThenParseRoundTrips) {
  ActionGroupFile g;
  g.servos = {1, 2, 5};
  for (std::uint16_t i = 0; i < 1020; ++i)
    g.actions.push_back({static_cast<std::uint16_t>(i * 29 % 30001),
                         {{1, static_cast<std::uint16_t>(i % 1001)},
                          {2, std::nullopt},
                          {5, static_cast<std::uint16_t>(1000 - i % 1001)}}});
  auto back = parse_action_group(format_action_group(g));
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(*back, g);
}

TEST(ActionGroupFile, ReadsFromDiskAndNamesAMissingFile) {
  auto path = std::filesystem::temp_directory_path() / "armctl-board-test.grp";
  std::ofstream(path) << "100 1=1\n";
  auto g = read_action_group_file(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(g.ok());
  EXPECT_EQ(g->actions.size(), 1u);
  auto missing = read_action_group_file("/nonexistent/x.grp");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().kind, ErrorKind::io);
  EXPECT_NE(missing.error().message.find("/nonexistent/x.grp"), std::string::npos);
}

struct BadFile {
  const char* text;
  const char* where;  // "g:LINE" or "g:LINE:COLUMN" that the message must start with
  const char* says;   // part of the explanation
};

class BadFiles : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadFiles, ErrorNamesLineAndProblem) {
  auto g = parse_action_group(GetParam().text, "g");
  ASSERT_FALSE(g.ok());
  const std::string& m = g.error().message;
  EXPECT_EQ(g.error().kind, ErrorKind::invalid_config);
  EXPECT_EQ(m.rfind(std::string(GetParam().where) + ":", 0), 0u) << m;
  EXPECT_NE(m.find(GetParam().says), std::string::npos) << m;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadFiles,
    ::testing::Values(
        BadFile{"", "g:1", "no actions"}, BadFile{"# only a comment\n\n", "g:3", "no actions"},
        BadFile{"100 1=500\nabc 1=500\n", "g:2:1", "time must be whole milliseconds"},
        BadFile{"30001 1=500\n", "g:1:1", "0..30000"}, BadFile{"-5 1=500\n", "g:1:1", "0..30000"},
        BadFile{"100\n", "g:1:4", "at least one servo=position"},
        BadFile{"100 1:500\n", "g:1:5", "expected servo=position"},
        BadFile{"100 0=500\n", "g:1:5", "servo ID must be a whole number 1..254"},
        BadFile{"100 1=500 255=1\n", "g:1:11", "1..254"},
        BadFile{"100 1=1001\n", "g:1:7", "position must be 0..1000"},
        BadFile{"100 1=abc\n", "g:1:7", "30deg"}, BadFile{"100 1=121deg\n", "g:1:7", "-120..120"},
        BadFile{"100 1=nandeg\n", "g:1:7", "-120..120"},
        BadFile{"100 1=500 1=600\n", "g:1:11", "appears twice"},
        BadFile{"100 1=500 2=500\n100 1=500 3=500\n", "g:2:11",
                "not in this group's servo set 1,2"},
        BadFile{"100 1=500 2=500\n100 1=500\n", "g:2:1", "every action must name the same 2"},
        BadFile{"servos 2\n100 1=500\n", "g:2:1", "header says 2"},
        BadFile{"servos 0\n", "g:1:8", "1..17"},
        BadFile{"servos 3 4\n", "g:1:1", "expected 'servos N'"},
        BadFile{"servos 2\nservos 2\n", "g:2:1", "second 'servos' header"},
        BadFile{"100 1=5\nservos 1\n", "g:2:1", "before the first action"},
        BadFile{"100 1=1 2=1 3=1 4=1 5=1 6=1 7=1 8=1 9=1 10=1 11=1 12=1 13=1 14=1 15=1 16=1 17=1 "
                "18=1\n",
                "g:1:1", "at most 17"}));

TEST(ActionGroupFile, MoreThan1020ActionsNamesTheLine) {
  std::string text;
  for (int i = 0; i < 1021; ++i) text += "10 1=500\n";
  auto g = parse_action_group(text, "g");
  ASSERT_FALSE(g.ok());
  EXPECT_EQ(g.error().message.rfind("g:1021:1:", 0), 0u) << g.error().message;
  EXPECT_NE(g.error().message.find("1020"), std::string::npos);
}

}  // namespace
}  // namespace armctl::files

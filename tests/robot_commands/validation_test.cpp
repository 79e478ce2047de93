// Encoders refuse bad values (naming field and allowed range); decoders refuse inconsistent
// frames with an error and never a partial result.
#include <gtest/gtest.h>

#include "protocol/robot_commands/messages.hpp"
#include "protocol/robot_commands/units.hpp"

namespace armctl::rc {
namespace {

const ServoRange kXarm = ServoRange::xarm();

void expect_refused(const Request& r, const std::string& words) {
  auto f = encode(r, kXarm);
  ASSERT_FALSE(f) << "encoded although invalid";
  EXPECT_EQ(f.error().kind, ErrorKind::invalid_argument);
  EXPECT_NE(f.error().message.find(words), std::string::npos) << f.error().message;
}

void expect_bad_frame(const Frame& f, const std::string& words) {
  auto r = decode_request(f, kXarm);
  ASSERT_FALSE(r) << "decoded: " << to_hex(encode_frame(f));
  EXPECT_EQ(r.error().kind, ErrorKind::protocol);
  EXPECT_NE(r.error().message.find(words), std::string::npos) << r.error().message;
}

TEST(EncodeRefuses, ValuesOutOfRange) {
  expect_refused(MultiServoMove{30001, {{1, 500}}}, "allowed 0..30000");
  expect_refused(MultiServoMove{100, {{1, 1001}}}, "position 1001");
  expect_refused(MultiServoMove{100, {{0, 500}}}, "servo 0 is not present");
  expect_refused(MultiServoMove{100, {{7, 500}}}, "allowed 1..6");
  expect_refused(MultiServoMove{100, {}}, "0 servo entries");
  expect_refused(MultiServoMove{100, {{1, 5}, {1, 6}}}, "more than once");
  expect_refused(ServoOffsetAdjust{1, 126}, "allowed -125..125");
  expect_refused(ServoOffsetAdjust{9, 0}, "servo 9");
  expect_refused(GroupRun{255, 1}, "group 255");
  expect_refused(GroupSpeed{1, 0}, "percentage 0");
  expect_refused(GroupDownloadBegin{1, 1021}, "allowed 1..1020");
  expect_refused(GroupDownloadBegin{1, 0}, "allowed 1..1020");
  expect_refused(GroupDownloadServoCount{1, 7}, "allowed 1..6");
  expect_refused(GroupDownloadBlocks{1, 5}, "allowed 1..4");
  expect_refused(GroupDownloadAction{1, 4, 0, 100, {{1, 500}}}, "block 4");
  expect_refused(GroupDownloadAction{1, 0, 255, 100, {{1, 500}}}, "index 255 is outside its block");
  expect_refused(MultiServoOff{{}}, "0 servos");
  expect_refused(ServoPositionRead{{1, 2, 3, 4, 5, 6, 1}}, "7 servos");
  expect_refused(ServoOffsetRead{{3, 3}}, "more than once");
  expect_refused(BusServoInfoWrite{1, 600, 500, 4500, 12000, 85, 0, 0}, "position limits");
  expect_refused(BusServoInfoWrite{1, 0, 1000, 4000, 12000, 85, 0, 0}, "voltage limits");
  expect_refused(BusServoInfoWrite{1, 0, 1000, 4500, 12000, 101, 0, 0}, "temperature limit 101");
  expect_refused(BusServoInfoWrite{1, 0, 1000, 4500, 12000, 85, 2, 0}, "led_status 2");
  expect_refused(BusServoInfoWrite{1, 0, 1000, 4500, 12000, 85, 0, 8}, "led_warning 8");
  expect_refused(ServoSpeed{1, static_cast<ServoMode>(2), 0}, "mode 2");
}

TEST(EncodeAccepts, EdgesOfEveryRange) {
  EXPECT_TRUE(encode(MultiServoMove{30000, {{1, 0}, {6, 1000}, {3, std::nullopt}}}, kXarm));
  EXPECT_TRUE(encode(ServoOffsetAdjust{6, -125}, kXarm));
  EXPECT_TRUE(encode(GroupErase{255}, kXarm));
  EXPECT_TRUE(encode(GroupSpeed{255, 1000}, kXarm));
  EXPECT_TRUE(encode(GroupDownloadBegin{254, 1020}, kXarm));
  EXPECT_TRUE(encode(GroupDownloadAction{0, 3, 254, 0, {{1, 500}}}, kXarm));
  EXPECT_TRUE(encode(MultiServoMove{0, {{7, 500}}}, ServoRange::of_count(7)));
}

TEST(ActionCount, RunOfBytesSumsToTheCount) {
  EXPECT_EQ(action_count_bytes(1), (std::vector<std::uint8_t>{1}));
  EXPECT_EQ(action_count_bytes(255), (std::vector<std::uint8_t>{255}));
  EXPECT_EQ(action_count_bytes(256), (std::vector<std::uint8_t>{255, 1}));
  EXPECT_EQ(action_count_bytes(300), (std::vector<std::uint8_t>{255, 45}));
  EXPECT_EQ(action_count_bytes(1020), (std::vector<std::uint8_t>{255, 255, 255, 255}));
  EXPECT_EQ(blocks_for_actions(255), 1);
  EXPECT_EQ(blocks_for_actions(256), 2);
  EXPECT_EQ(blocks_for_actions(1020), 4);
}

TEST(DecodeRefuses, InconsistentFrames) {
  expect_bad_frame(Frame{3, {2, 0xE8, 0x03, 1, 0xF4, 0x01}}, "count 2");
  expect_bad_frame(Frame{3, {1, 0xE8}}, "at least 3");
  expect_bad_frame(Frame{3, {1, 0x31, 0x75, 1, 0xF4, 0x01}}, "time 30001");
  expect_bad_frame(Frame{20, {3, 1, 2}}, "count 3");
  expect_bad_frame(Frame{21, {}}, "count byte");
  expect_bad_frame(Frame{6, {1, 2}}, "DATA is 2 bytes");
  expect_bad_frame(Frame{7, {1}}, "DATA is 1 bytes");
  expect_bad_frame(Frame{15, {0}}, "DATA is 1 bytes");
  expect_bad_frame(Frame{24, {1, 0x7F, 0x00}}, "offset 127");
  expect_bad_frame(Frame{26, {1, 2, 0, 0}}, "mode 2");
  expect_bad_frame(Frame{27, {1, 0, 0}}, "DATA is 3 bytes");
  // GroupDownload: each sub-command's layout and the spec's consistency rules.
  expect_bad_frame(Frame{5, {9, 1}}, "sub-command 9");
  expect_bad_frame(Frame{5, {1, 4}}, "GroupDownload begin");
  expect_bad_frame(Frame{5, {1, 4, 255, 255, 255, 255, 1}}, "1021");
  expect_bad_frame(Frame{5, {2, 4, 1, 3, 0}}, "group 00 count 00");
  expect_bad_frame(Frame{5, {3, 4, 0, 0, 2}}, "in order");
  expect_bad_frame(Frame{5, {3, 4, 0, 0, 1, 2, 3, 4}}, "GroupDownload blocks");
  expect_bad_frame(Frame{5, {4, 4, 0, 7, 0x0B, 0x20, 0x03, 1, 0x90, 0x01, 2, 0xF4, 0x01}},
                   "byte count 11 disagrees");
  expect_bad_frame(Frame{5, {4, 4, 0, 255, 5, 0x20, 0x03, 1, 0x90, 0x01}},
                   "index 255 is outside its block");
  expect_bad_frame(Frame{5, {4, 4, 0, 7, 4, 0x20, 0x03, 1, 0x90}}, "not 2 + 3 n");
  expect_bad_frame(Frame{5, {5, 4, 0}}, "GroupDownload end");
}

TEST(DecodeBoardMessage, RefusesInconsistentReplies) {
  EXPECT_FALSE(decode_board_message(Frame{21, {2, 1, 0xF4, 0x01}}));     // count 2, one entry
  EXPECT_FALSE(decode_board_message(Frame{23, {1, 3, 0x7F}}));           // offset 127
  EXPECT_FALSE(decode_board_message(Frame{5, {1, 1}}));                  // not `sub 00`
  EXPECT_FALSE(decode_board_message(Frame{5, {6, 0}}));                  // sub 6
  EXPECT_FALSE(decode_board_message(Frame{8, {2, 3}}));                  // 2 bytes
  EXPECT_FALSE(decode_board_message(Frame{28, std::vector<std::uint8_t>(18)}));
  EXPECT_FALSE(decode_board_message(Frame{3, {}}));  // a request, not something a board sends
}

TEST(DecodeBoardMessage, RealBoardVariants) {
  EXPECT_EQ(std::get<GroupNotification>(decode_board_message(Frame{6, {}}).value()),
            (GroupNotification{GroupEventKind::started, {}, {}}));
  EXPECT_EQ(std::get<GroupNotification>(decode_board_message(Frame{7, {}}).value()).kind,
            GroupEventKind::stopped);
  // Encoding a "finished" without group/count gives the CMD 7 variant, never CMD 8 (which
  // would read as the GroupErase reply).
  auto f = encode(BoardMessage{GroupNotification{GroupEventKind::finished, {}, {}}});
  ASSERT_TRUE(f);
  EXPECT_EQ(f->cmd, 7);
}

TEST(Units, DegreesAndPositions) {
  EXPECT_DOUBLE_EQ(position_to_degrees(500), 0.0);
  EXPECT_DOUBLE_EQ(position_to_degrees(1000), 120.0);
  EXPECT_DOUBLE_EQ(position_to_degrees(0), -120.0);
  EXPECT_EQ(degrees_to_position(30), 625);
  EXPECT_EQ(degrees_to_position(-120), 0);
  for (int p = 0; p <= 1000; ++p) EXPECT_EQ(degrees_to_position(position_to_degrees(p)), p);
}

}  // namespace
}  // namespace armctl::rc

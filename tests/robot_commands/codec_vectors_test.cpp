// Every vector of robot-commands.json, byte-exact both ways, and every malformed case.
#include <gtest/gtest.h>

#include "protocol/robot_commands/frame_receiver.hpp"
#include "protocol/robot_commands/messages.hpp"
#include "rc_vectors.hpp"

namespace armctl::rc {
namespace {

using testing::load_vectors;
using testing::malformed_case;

Frame single_frame(const std::vector<std::uint8_t>& bytes) {
  FrameReceiver rx;
  rx.feed(bytes);
  EXPECT_EQ(rx.pending_frames(), 1u);
  EXPECT_EQ(rx.discarded_bytes(), 0u);
  auto f = rx.next();
  if (!f) throw std::runtime_error("no frame");
  return *f;
}

TEST(RcVectors, FileHasTheExpectedCases) {
  EXPECT_EQ(load_vectors().size(), 30u);
  EXPECT_EQ(testing::load_malformed().size(), 5u);
}

TEST(RcVectors, EveryVectorDecodesAndReencodesByteExact) {
  for (const auto& v : load_vectors()) {
    SCOPED_TRACE(v.name);
    const Frame f = single_frame(v.bytes);
    EXPECT_EQ(f.cmd, v.cmd);
    EXPECT_EQ(encode_frame(f), v.bytes);
    if (v.host_to_board) {
      auto request = decode_request(f, ServoRange::xarm());
      ASSERT_TRUE(request) << request.error().message;
      EXPECT_EQ(static_cast<std::uint8_t>(command_of(*request)), v.cmd);
      auto again = encode(*request, ServoRange::xarm());
      ASSERT_TRUE(again) << again.error().message;
      EXPECT_EQ(encode_frame(*again), v.bytes);
    } else {
      auto message = decode_board_message(f);
      ASSERT_TRUE(message) << message.error().message;
      EXPECT_EQ(cmd_byte_of(*message), v.cmd);
      auto again = encode(*message);
      ASSERT_TRUE(again) << again.error().message;
      EXPECT_EQ(encode_frame(*again), v.bytes);
    }
  }
}

// Field-level checks: the typed values are what the vector names say.
TEST(RcVectors, TypedValuesMatchTheVectorNames) {
  auto req = [](const char* name) {
    for (const auto& v : load_vectors()) {
      if (v.name == name) return decode_request(single_frame(v.bytes), ServoRange::xarm()).value();
    }
    throw std::runtime_error(name);
  };
  auto board = [](const char* name) {
    for (const auto& v : load_vectors()) {
      if (v.name == name) return decode_board_message(single_frame(v.bytes)).value();
    }
    throw std::runtime_error(name);
  };
  const auto move = std::get<MultiServoMove>(req("MultiServoMove 2 servos, 1000 ms"));
  EXPECT_EQ(move.time_ms, 1000);
  ASSERT_EQ(move.targets.size(), 2u);
  EXPECT_EQ(move.targets[0], (ServoTarget{1, 500}));
  EXPECT_EQ(move.targets[1], (ServoTarget{2, std::nullopt}));

  EXPECT_EQ(std::get<GroupRun>(req("GroupRun group 2, 3 times")), (GroupRun{2, 3}));
  EXPECT_EQ(std::get<GroupRun>(req("GroupRun group 0, continuous")), (GroupRun{0, 0}));
  EXPECT_EQ(std::get<GroupErase>(req("GroupErase all")), (GroupErase{255}));
  EXPECT_EQ(std::get<GroupSpeed>(req("GroupSpeed group 1 at 200 %")), (GroupSpeed{1, 200}));
  EXPECT_EQ(std::get<ServoOffsetAdjust>(req("ServoOffsetAdjust servo 4 by -20")),
            (ServoOffsetAdjust{4, -20}));
  EXPECT_EQ(std::get<ServoSpeed>(req("ServoSpeed servo 2 motor mode 500")),
            (ServoSpeed{2, ServoMode::motor, 500}));
  EXPECT_EQ(std::get<GroupDownloadBegin>(req("GroupDownload begin group 4, 300 actions")),
            (GroupDownloadBegin{4, 300}));
  EXPECT_EQ(std::get<GroupDownloadServoCount>(req("GroupDownload servos per action = 3")),
            (GroupDownloadServoCount{4, 3}));
  EXPECT_EQ(std::get<GroupDownloadBlocks>(req("GroupDownload blocks 0 and 1 (<= 510 actions)")),
            (GroupDownloadBlocks{4, 2}));
  const auto action = std::get<GroupDownloadAction>(
      req("GroupDownload action block 0 index 7, 800 ms, 3 servos"));
  EXPECT_EQ(action.block, 0);
  EXPECT_EQ(action.index, 7);
  EXPECT_EQ(action.time_ms, 800);
  EXPECT_EQ(action.targets,
            (std::vector<ServoTarget>{{1, 400}, {2, 500}, {3, 600}}));
  const auto info = std::get<BusServoInfoWrite>(req("BusServoInfoWrite servo 1"));
  EXPECT_EQ(info, (BusServoInfoWrite{1, 0, 1000, 4500, 12000, 85, 0, 3}));

  EXPECT_EQ(std::get<BatteryVoltageReply>(board("GetBatteryVoltage reply 7500 mV")).millivolts,
            7500);
  EXPECT_EQ(std::get<ServoOffsetReply>(board("ServoOffsetRead reply (+10, -20)")).offsets,
            (std::vector<ServoOffset>{{3, 10}, {4, -20}}));
  EXPECT_EQ(std::get<ServoPositionReply>(board("ServoPositionRead reply")).positions,
            (std::vector<ServoPosition>{{1, 500}, {2, 300}}));
  const auto r = std::get<BusServoInfoReply>(board("BusServoInfoRead reply"));
  EXPECT_EQ(r.offset, -5);
  EXPECT_EQ(r.position, 498);
  EXPECT_EQ(r.temp, 41);
  EXPECT_EQ(r.millivolts, 7400);
  EXPECT_EQ(std::get<GroupEraseReply>(board("GroupErase reply")), GroupEraseReply{});
  EXPECT_EQ(std::get<GroupDownloadAck>(board("GroupDownload ack of sub 1")).sub, 1);
  EXPECT_EQ(std::get<GroupNotification>(board("notification: group 2 started, 3 times")),
            (GroupNotification{GroupEventKind::started, 2, 3}));
  EXPECT_EQ(std::get<GroupNotification>(board("notification: stopped")),
            (GroupNotification{GroupEventKind::stopped, {}, {}}));
  EXPECT_EQ(std::get<GroupNotification>(board("notification: group 2 finished")),
            (GroupNotification{GroupEventKind::finished, 2, 3}));
}

TEST(RcMalformed, LenBelowTwoIsDiscarded) {
  const auto m = malformed_case("LEN < 2");
  FrameReceiver rx;
  rx.feed(m.bytes);
  EXPECT_EQ(rx.pending_frames(), 0u);
  EXPECT_EQ(rx.bad_lengths(), 1u);
  // Resynchronises: a good frame right after is found.
  rx.feed(std::vector<std::uint8_t>{0x55, 0x55, 0x02, 0x0F});
  auto f = rx.next();
  ASSERT_TRUE(f);
  EXPECT_EQ(*f, (Frame{15, {}}));
}

TEST(RcMalformed, LeadingGarbageSkippedThenGetBatteryVoltage) {
  const auto m = malformed_case("leading garbage");
  FrameReceiver rx;
  rx.feed(m.bytes);
  EXPECT_EQ(rx.discarded_bytes(), 1u);
  auto f = rx.next();
  ASSERT_TRUE(f);
  auto request = decode_request(*f, ServoRange::xarm());
  ASSERT_TRUE(request);
  EXPECT_TRUE(std::holds_alternative<GetBatteryVoltage>(*request));
}

TEST(RcMalformed, CountThatDisagreesWithDataIsRefused) {
  const auto m = malformed_case("ServoPositionRead count 3");
  const Frame f = single_frame(m.bytes);
  auto request = decode_request(f, ServoRange::xarm());
  ASSERT_FALSE(request);
  EXPECT_EQ(request.error().kind, ErrorKind::protocol);
  EXPECT_NE(request.error().message.find("count 3"), std::string::npos)
      << request.error().message;
}

TEST(RcMalformed, UnknownCmdIsRefusedBothWays) {
  const auto m = malformed_case("unknown CMD 0x63");
  const Frame f = single_frame(m.bytes);
  auto request = decode_request(f, ServoRange::xarm());
  ASSERT_FALSE(request);
  EXPECT_NE(request.error().message.find("0x63"), std::string::npos);
  EXPECT_FALSE(decode_board_message(f));
  // And the host library cannot even build it: there is no typed message for 0x63.
  EXPECT_FALSE(command_from_byte(0x63));
}

TEST(RcMalformed, ServoSevenOnSixServoArmIsRefusedButFineOnSeven) {
  const auto m = malformed_case("MultiServoMove to servo 7");
  const Frame f = single_frame(m.bytes);
  auto on_xarm = decode_request(f, ServoRange::xarm());
  ASSERT_FALSE(on_xarm);
  EXPECT_NE(on_xarm.error().message.find("servo 7"), std::string::npos);
  EXPECT_NE(on_xarm.error().message.find("1..6"), std::string::npos);
  EXPECT_TRUE(decode_request(f, ServoRange::of_count(7)));
  // The encoder refuses the same move for a 6-servo arm.
  auto typed = std::get<MultiServoMove>(decode_request(f, ServoRange::of_count(7)).value());
  EXPECT_FALSE(encode(typed, ServoRange::xarm()));
}

}  // namespace
}  // namespace armctl::rc

// JointFaultRead and JointFaultClear (CMD 40 and 41, armctl extensions): their codecs, the
// SDK against a board that answers them (scripted) and against boards that do not (the
// emulated xArm, a silent scripted board): one extension_timeout once, then nothing more
// is sent.
#include <gtest/gtest.h>

#include "devices/robot_commands/client.hpp"
#include "protocol/robot_commands/joint_faults.hpp"
#include "sim_links.hpp"

namespace armctl::robot_commands {
namespace {

using namespace std::chrono_literals;
using testing::EmulatedLink;
using testing::ScriptedLink;

rc::JointFaultReport runaway_report(std::uint8_t servo) {
  rc::JointFaultReport r;
  r.servo = servo;
  r.answering = true;
  r.words_read = true;
  r.last_failure = 940;
  r.following_lost = 1;
  r.words = {1, 0, 0, 0, 1, 0, 0};
  return r;
}

TEST(JointFaultCodec, ReplyRoundTripsAndItsBytesAreAsDocumented) {
  const auto report = runaway_report(3);
  const rc::Frame f = rc::encode_joint_fault_reply(report);
  // docs/mega-controller.md: servo flags last_failure following_lost word0..word6.
  const std::vector<std::uint8_t> expected{3, 0x05, 0xAC, 0x03, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0};
  EXPECT_EQ(f.cmd, 40);
  EXPECT_EQ(f.data, expected);
  auto back = rc::decode_joint_fault_reply(f);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(*back, report);
}

TEST(JointFaultCodec, MalformedRepliesAndBadServosAreRefusedWithReasons) {
  rc::Frame f = rc::encode_joint_fault_reply(runaway_report(2));
  f.data.pop_back();
  auto short_reply = rc::decode_joint_fault_reply(f);
  ASSERT_FALSE(short_reply);
  EXPECT_NE(short_reply.error().message.find("19 bytes of DATA (expected 20)"), std::string::npos)
      << short_reply.error().message;
  f = rc::encode_joint_fault_reply(runaway_report(2));
  f.data[1] = 0x40;
  auto flags = rc::decode_joint_fault_reply(f);
  ASSERT_FALSE(flags);
  EXPECT_NE(flags.error().message.find("flags 0x40"), std::string::npos) << flags.error().message;
  auto bad_servo = rc::encode_joint_fault_read(8, rc::ServoRange::of_count(7));
  ASSERT_FALSE(bad_servo);
  EXPECT_EQ(bad_servo.error().kind, ErrorKind::invalid_argument);
  EXPECT_NE(bad_servo.error().message.find("servo 8"), std::string::npos);
}

TEST(JointFaultClient, ABoardThatAnswersIsRead) {
  ScriptedLink link([](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd != 40) return {};
    return {{2ms, rc::Frame{6, {1, 1, 0}}},  // a notification meanwhile is kept
            {5ms, rc::encode_joint_fault_reply(runaway_report(f.data.at(0)))}};
  });
  Client c(link, ClientOptions{.servo_count = 7});
  auto r = c.read_joint_faults(5);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(r->has_value());
  EXPECT_EQ(**r, runaway_report(5));
  EXPECT_EQ(c.has_joint_faults(), true);
  EXPECT_EQ(c.pending_events(), 1u);
  EXPECT_FALSE(c.read_joint_faults(8)) << "servo 8 is not on a 7-servo board";
}

TEST(JointFaultClient, AnAnswerForAnotherServoIsAProtocolError) {
  ScriptedLink link([](const rc::Frame&) -> std::vector<ScriptedLink::Timed> {
    return {{1ms, rc::encode_joint_fault_reply(runaway_report(2))}};
  });
  Client c(link, ClientOptions{.servo_count = 7});
  auto r = c.read_joint_faults(4);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::protocol);
  EXPECT_NE(r.error().message.find("asked for servo 4"), std::string::npos) << r.error().message;
}

TEST(JointFaultClient, TheEmulatedXarmIgnoresItOnceAndIsNeverAskedAgain) {
  EmulatedLink link(9600);
  Client c(link, ClientOptions{.extension_timeout = 250ms});
  const TimePoint start = link.sim_clock().now();
  auto first = c.read_joint_faults(1);
  ASSERT_TRUE(first) << "no error for a board without the extension: " << first.error().message;
  EXPECT_FALSE(first->has_value());
  EXPECT_EQ(link.sim_clock().now() - start, 250ms) << "bounded by extension_timeout";
  EXPECT_EQ(c.has_joint_faults(), false);
  EXPECT_EQ(link.emulator().board().stats().unknown_command, 1u) << "the board ignored CMD 40";
  const std::size_t sent = link.sent.size();
  const TimePoint again = link.sim_clock().now();
  auto second = c.read_joint_faults(2);
  ASSERT_TRUE(second);
  EXPECT_FALSE(second->has_value());
  EXPECT_EQ(link.sent.size(), sent) << "nothing sent once the board is known not to answer";
  EXPECT_EQ(link.sim_clock().now(), again);
  // The board still answers everything else.
  auto mv = c.battery_millivolts();
  EXPECT_TRUE(mv) << mv.error().message;
}

TEST(JointFaultClient, ABoardThatAnsweredAndFallsSilentIsATimeout) {
  bool answer = true;
  ScriptedLink link([&](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd != 40 || !answer) return {};
    return {{3ms, rc::encode_joint_fault_reply(runaway_report(f.data.at(0)))}};
  });
  Client c(link, ClientOptions{.servo_count = 7});
  ASSERT_TRUE(c.read_joint_faults(1));
  answer = false;
  auto r = c.read_joint_faults(1);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::timeout);
  EXPECT_NE(r.error().message.find("though it answered before"), std::string::npos) << r.error().message;
}

TEST(JointFaultClient, ALateReplyIsStaleNotTakenForTheNextRead) {
  ScriptedLink link([](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd == 40) return {{300ms, rc::encode_joint_fault_reply(runaway_report(1))}};
    if (f.cmd == 15) return {{5ms, rc::Frame{15, {0xC0, 0x5D}}}};
    return {};
  });
  Client c(link, ClientOptions{.servo_count = 7, .extension_timeout = 250ms});
  auto r = c.read_joint_faults(1);
  ASSERT_TRUE(r);
  EXPECT_FALSE(r->has_value());
  link.sim_clock().advance(100ms);
  auto mv = c.battery_millivolts();
  ASSERT_TRUE(mv) << mv.error().message;
  EXPECT_EQ(*mv, 24000);
  EXPECT_EQ(c.stats().stale_replies, 1u);
  EXPECT_EQ(c.stats().unreadable_frames, 0u);
}

TEST(JointFaultClearCodec, RequestAndReplyAreAsDocumented) {
  auto request = rc::encode_joint_fault_clear(3, rc::ServoRange::of_count(7));
  ASSERT_TRUE(request);
  EXPECT_EQ(request->cmd, 41);
  EXPECT_EQ(request->data, (std::vector<std::uint8_t>{3}));
  // docs/mega-controller.md: servo status:u16; 510 = 100 + 10 x 41, the joint's success.
  const rc::Frame reply = rc::encode_joint_fault_clear_reply({3, 510});
  EXPECT_EQ(reply.data, (std::vector<std::uint8_t>{3, 0xFE, 0x01}));
  auto back = rc::decode_joint_fault_clear_reply(reply);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(back->cleared());
  EXPECT_FALSE((rc::JointFaultClearReply{3, 990}).cleared());
  rc::Frame torn = reply;
  torn.data.pop_back();
  auto bad = rc::decode_joint_fault_clear_reply(torn);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("2 bytes of DATA (expected 3)"), std::string::npos) << bad.error().message;
  auto bad_servo = rc::encode_joint_fault_clear(0, rc::ServoRange::of_count(7));
  ASSERT_FALSE(bad_servo);
  EXPECT_NE(bad_servo.error().message.find("servo 0"), std::string::npos) << bad_servo.error().message;
}

TEST(JointFaultClearClient, TheJointsStatusComesBackAndAnotherServosIsAnError) {
  std::uint16_t status = 510;
  std::uint8_t answer_for = 0;
  ScriptedLink link([&](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd != 41) return {};
    const std::uint8_t servo = answer_for != 0 ? answer_for : f.data.at(0);
    return {{9ms, rc::encode_joint_fault_clear_reply({servo, status})}};
  });
  Client c(link, ClientOptions{.servo_count = 7});
  auto cleared = c.clear_joint_faults(4);
  ASSERT_TRUE(cleared) << cleared.error().message;
  ASSERT_TRUE(cleared->has_value());
  EXPECT_TRUE((*cleared)->cleared());
  EXPECT_EQ(c.has_joint_faults(), true);
  status = 990;
  auto silent_joint = c.clear_joint_faults(4);
  ASSERT_TRUE(silent_joint);
  EXPECT_EQ((*silent_joint)->status, 990);
  answer_for = 2;
  auto other = c.clear_joint_faults(4);
  ASSERT_FALSE(other);
  EXPECT_EQ(other.error().kind, ErrorKind::protocol);
}

TEST(JointFaultClearClient, ABoardThatIgnoredTheReadIsNotAskedToClear) {
  EmulatedLink link(9600);
  Client c(link, ClientOptions{.extension_timeout = 250ms});
  auto first = c.clear_joint_faults(1);
  ASSERT_TRUE(first) << first.error().message;
  EXPECT_FALSE(first->has_value());
  EXPECT_EQ(link.emulator().board().stats().unknown_command, 1u) << "the board ignored CMD 41";
  const std::size_t sent = link.sent.size();
  auto read = c.read_joint_faults(1);
  ASSERT_TRUE(read);
  EXPECT_FALSE(read->has_value());
  EXPECT_EQ(link.sent.size(), sent) << "one extension: nothing more sent";
}

}  // namespace
}  // namespace armctl::robot_commands

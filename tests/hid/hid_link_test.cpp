// The SDK over HID against a fake board that behaves as real xArm boards are reported to
// (fake_xarm_hid.hpp), on simulated time: slow replies, a deaf spell after opening, a lost
// reply, a second program on the node, an ignored combined servo-off, a clone's product
// string. Each case also shows the old behaviour failing, so the fake really misbehaves.
#include <gtest/gtest.h>

#include "devices/robot_commands/client.hpp"
#include "devices/robot_commands/hid_link.hpp"
#include "fake_hid_backend.hpp"
#include "protocol/robot_commands/command_codes.hpp"

namespace armctl::robot_commands {
namespace {

using namespace std::chrono_literals;
using armctl::testing::FakeHidBackend;
using armctl::testing::FakeHidBehaviour;

FakeHidBehaviour with(void (*set)(FakeHidBehaviour&)) {
  FakeHidBehaviour b;
  set(b);
  return b;
}

ClientOptions old_defaults() { return ClientOptions{}; }  // 500 ms, one attempt

long long ms(Duration d) { return std::chrono::duration_cast<std::chrono::milliseconds>(d).count(); }

int count_cmd(const FakeHidBackend& b, rc::Command cmd) {
  int n = 0;
  for (const auto& f : const_cast<FakeHidBackend&>(b).board().requests()) {
    if (f.cmd == static_cast<std::uint8_t>(cmd)) ++n;
  }
  return n;
}

TEST(HidTimings, DefaultsAreTheDocumentedOnes) {
  const auto o = hid_client_options(6);
  EXPECT_GE(o.reply_timeout, 1500ms);  // issue 15: at least 1.5 s
  EXPECT_GT(o.read_attempts, 1);
  EXPECT_GT(o.poll_interval, ClientOptions{}.poll_interval);
  EXPECT_TRUE(o.servo_off_per_servo);
  EXPECT_TRUE(ClientOptions{}.servo_off_per_servo);  // serial too, unless told the board is ours
}

TEST(HidLate, PositionReadAnsweredAfter450ms) {
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.reply_delay = 450ms; }));
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  const TimePoint t0 = fake.clock().now();
  auto ps = c.read_all_positions();
  ASSERT_TRUE(ps) << ps.error().message;
  EXPECT_EQ(ps->size(), 6u);
  EXPECT_EQ(ms(fake.clock().now() - t0), 450);
  EXPECT_EQ(c.stats().read_retries, 0u);
}

TEST(HidLate, BoardThatAnswersOnly1200msAfterOpenIsWaitedFor) {
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.reply_delay = 20ms; b.hold_after_open = 1200ms; }));
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  ASSERT_TRUE(await_first_contact(c));
  EXPECT_EQ(ms(fake.clock().now().time_since_epoch()), 1200);
  EXPECT_EQ(count_cmd(fake, rc::Command::GetBatteryVoltage), 1);  // one request, answered late
  auto ps = c.read_all_positions();
  ASSERT_TRUE(ps) << ps.error().message;
}

TEST(HidLate, OldSingle500msWaitFailsOnTheSameBoard) {
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.reply_delay = 20ms; b.hold_after_open = 1200ms; }));
  auto link = HidLink::open_board("", fake);
  Client c(*link, old_defaults());
  auto first = await_first_contact(c);
  ASSERT_FALSE(first);
  EXPECT_EQ(first.error().kind, ErrorKind::timeout);
  EXPECT_NE(first.error().message.find("did not answer its first request"), std::string::npos)
      << first.error().message;
  EXPECT_NE(first.error().message.find("fwupd"), std::string::npos);
}

TEST(HidFirstContact, DeafBoardIsAskedAgainUntilItAnswers) {
  // Requests in the first 1.2 s are lost: the first battery read must be sent again.
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.reply_delay = 30ms; b.deaf_after_open = 1200ms; }));
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  ASSERT_TRUE(await_first_contact(c));
  EXPECT_EQ(count_cmd(fake, rc::Command::GetBatteryVoltage), 2);
  EXPECT_EQ(c.stats().read_retries, 1u);
  EXPECT_EQ(ms(fake.clock().now().time_since_epoch()), 1500 + 30);
}

TEST(HidRetry, DroppedReplyIsRiddenOutBySendingTheReadAgain) {
  FakeHidBehaviour b;
  b.reply_delay = 100ms;
  b.drop_replies = {2};
  FakeHidBackend fake(b);
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  ASSERT_TRUE(c.battery_millivolts());  // reply 1
  const TimePoint t0 = fake.clock().now();
  auto ps = c.read_all_positions();     // reply 2 lost, reply 3 answers the second attempt
  ASSERT_TRUE(ps) << ps.error().message;
  EXPECT_EQ(c.stats().read_retries, 1u);
  EXPECT_EQ(count_cmd(fake, rc::Command::ServoPositionRead), 2);
  EXPECT_EQ(ms(fake.clock().now() - t0), 1500 + 100);

  // The old single attempt fails on the same fault.
  FakeHidBackend fake2(b);
  auto link2 = HidLink::open_board("", fake2);
  Client old(*link2, old_defaults());
  ASSERT_TRUE(old.battery_millivolts());
  EXPECT_EQ(old.read_all_positions().error().kind, ErrorKind::timeout);
}

TEST(HidRetry, RetriesAreBoundedAndSaySo) {
  FakeHidBehaviour b;
  b.drop_replies = {1, 2, 3, 4};
  FakeHidBackend fake(b);
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  auto mv = c.battery_millivolts();
  ASSERT_FALSE(mv);
  EXPECT_EQ(mv.error().kind, ErrorKind::timeout);
  EXPECT_NE(mv.error().message.find("sent 3 times"), std::string::npos) << mv.error().message;
  EXPECT_EQ(count_cmd(fake, rc::Command::GetBatteryVoltage), 3);
  EXPECT_EQ(ms(fake.clock().now().time_since_epoch()), 3 * 1500);
}

TEST(HidRetry, CommandsThatActAreNeverSentTwice) {
  FakeHidBehaviour b;
  b.drop_replies = {1, 2, 3};
  FakeHidBackend fake(b);
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  ASSERT_TRUE(c.move({{1, 300}}, 500));
  auto erase = c.erase_group(3);  // its reply is lost: an error, not a second erase
  ASSERT_FALSE(erase);
  EXPECT_EQ(count_cmd(fake, rc::Command::MultiServoMove), 1);
  EXPECT_EQ(count_cmd(fake, rc::Command::GroupErase), 1);
}

TEST(HidRetry, LateAnswerToAnEarlierAttemptIsNotTakenForTheNextRequest) {
  // Replies take 1.6 s, longer than the 1.5 s wait: attempt 1's reply answers attempt 2,
  // and attempt 2's own reply arrives later. It must not be taken for the next request.
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.reply_delay = 1600ms; }));
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  ASSERT_TRUE(c.move({{2, 100}}, 0));
  fake.clock().advance(1s);
  auto first = c.read_positions({2});
  ASSERT_TRUE(first) << first.error().message;
  fake.clock().advance(2s);  // attempt 2's reply (the old position) has arrived meanwhile
  ASSERT_TRUE(c.move({{2, 900}}, 0));
  fake.clock().advance(1s);
  auto second = c.read_positions({2});
  ASSERT_TRUE(second) << second.error().message;
  EXPECT_EQ(c.stats().stale_replies, 1u);
  EXPECT_NEAR((*second)[0].position, 900, 5);
}

TEST(HidServoOff, OneFramePerServoSwitchesEveryServoOff) {
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.ignore_combined_servo_off = true; }));
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  ASSERT_TRUE(c.move({{1, 400}, {2, 400}, {3, 400}, {4, 400}, {5, 400}, {6, 400}}, 0));
  ASSERT_TRUE(c.servos_off(c.all_servos()));
  for (std::uint8_t s = 1; s <= 6; ++s) EXPECT_FALSE(fake.board().servos().torque(s)) << int(s);
  const auto& req = fake.board().requests();
  int off_frames = 0;
  for (const auto& f : req) {
    if (f.cmd != static_cast<std::uint8_t>(rc::Command::MultiServoOff)) continue;
    ++off_frames;
    EXPECT_EQ(f.data.at(0), 1);  // count 1
  }
  EXPECT_EQ(off_frames, 6);
  // Read back afterwards: the answer proves the board handled the off frames.
  EXPECT_EQ(req.back().cmd, static_cast<std::uint8_t>(rc::Command::ServoPositionRead));
}

TEST(HidServoOff, CombinedFrameLeavesServosStiffOnSuchABoard) {
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.ignore_combined_servo_off = true; }));
  auto link = HidLink::open_board("", fake);
  auto options = hid_client_options();
  options.servo_off_per_servo = false;  // as for a board known to be ours
  Client c(*link, options);
  ASSERT_TRUE(c.move({{1, 400}, {2, 400}}, 0));
  ASSERT_TRUE(c.servos_off({1, 2}));
  EXPECT_TRUE(fake.board().servos().torque(1));
  EXPECT_TRUE(fake.board().servos().torque(2));
}

TEST(HidServoOff, ReadBackFailureIsReported) {
  FakeHidBehaviour b;
  b.drop_replies = {1, 2, 3};
  FakeHidBackend fake(b);
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  auto off = c.servos_off({1});
  ASSERT_FALSE(off);
  EXPECT_NE(off.error().message.find("read-back"), std::string::npos) << off.error().message;
  EXPECT_FALSE(fake.board().servos().torque(1));  // the frame itself was sent once and acted
  EXPECT_EQ(count_cmd(fake, rc::Command::MultiServoOff), 1);
}

TEST(HidServoOff, BadListSendsNothing) {
  FakeHidBackend fake;
  auto link = HidLink::open_board("", fake);
  Client c(*link, hid_client_options());
  EXPECT_EQ(c.servos_off({1, 9}).error().kind, ErrorKind::invalid_argument);
  EXPECT_EQ(c.servos_off({1, 1}).error().kind, ErrorKind::invalid_argument);
  EXPECT_TRUE(fake.board().requests().empty());
}

TEST(HidSecondOpener, OtherProgramIsNamedInWarningsAndErrors) {
  // Another program reads servo 1 every 40 ms; its replies reach our handle too.
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.reply_delay = 100ms; b.other_opener_every = 40ms; }));
  auto link = HidLink::open_board("", fake);
  ASSERT_EQ(link->warnings().size(), 1u);
  EXPECT_NE(link->warnings()[0].find("fake-poller (pid 4242)"), std::string::npos);
  EXPECT_NE(link->describe().find("also open in fake-poller (pid 4242)"), std::string::npos);
  Client c(*link, hid_client_options());
  fake.clock().advance(50ms);  // the other program asked at 40 ms: its reply is due first
  auto ps = c.read_all_positions();
  ASSERT_FALSE(ps);  // the other program's reply (servo 1 only) came first
  EXPECT_EQ(ps.error().kind, ErrorKind::protocol);
  EXPECT_NE(ps.error().message.find("fake-poller (pid 4242)"), std::string::npos)
      << ps.error().message;
  EXPECT_GT(fake.board().other_opener_requests(), 0);
}

TEST(HidSecondOpener, EveryHandleGetsEveryReply) {
  // Two handles on one node, as hidraw allows when nobody locks (HidDevice does lock).
  FakeHidBackend fake(with([](FakeHidBehaviour& b) { b.reply_delay = 100ms; }));
  auto mine = HidLink::open_board("", fake);
  auto theirs = HidLink::open_board("", fake);
  Client me(*mine, hid_client_options());
  Client them(*theirs, hid_client_options());

  // Their answered read also reached our handle; it arrived before our request, so it is
  // counted as stale and not taken for our answer.
  ASSERT_TRUE(them.read_positions({1}));
  auto ours = me.read_all_positions();
  ASSERT_TRUE(ours) << ours.error().message;
  EXPECT_EQ(me.stats().stale_replies, 1u);

  // Their request still on its way when we ask: its reply comes first and cannot be told
  // from ours (no sequence numbers). This is why armctl locks the node.
  auto read_one = rc::encode(rc::ServoPositionRead{{1}}, rc::ServoRange::of_count(6));
  ASSERT_TRUE(read_one);
  theirs->send(*read_one);
  fake.clock().advance(10ms);
  auto mixed = me.read_all_positions();
  ASSERT_FALSE(mixed);
  EXPECT_EQ(mixed.error().kind, ErrorKind::protocol);
  EXPECT_NE(mixed.error().message.find("answered for 1"), std::string::npos)
      << mixed.error().message;
}

TEST(HidOpen, ExplicitPathOpensACloneWithAWarning) {
  FakeHidBackend fake;
  fake.devices[0].product = "XARM-CLONE";
  EXPECT_THROW(HidLink::open_board("", fake), ArmctlError);  // not found as an xArm board
  auto link = HidLink::open_board(FakeHidBackend::kPath, fake);
  ASSERT_EQ(link->warnings().size(), 1u);
  EXPECT_NE(link->warnings()[0].find("\"XARM-CLONE\", not an xArm board"), std::string::npos)
      << link->warnings()[0];
  Client c(*link, hid_client_options());
  EXPECT_TRUE(c.battery_millivolts());
}

TEST(HidOpen, ExplicitPathNotListedIsOpenedWithAWarning) {
  FakeHidBackend fake;
  fake.devices.clear();
  auto link = HidLink::open_board(FakeHidBackend::kPath, fake);
  ASSERT_EQ(link->warnings().size(), 1u);
  EXPECT_NE(link->warnings()[0].find("not listed"), std::string::npos);
}

TEST(HidOpen, XarmBoardByPathOrSerialHasNoWarning) {
  FakeHidBackend fake;
  EXPECT_TRUE(HidLink::open_board(FakeHidBackend::kPath, fake)->warnings().empty());
  EXPECT_TRUE(HidLink::open_board("FAKE0001", fake)->warnings().empty());
  try {
    HidLink::open_board("NOPE", fake);
    FAIL() << "opened a board that is not there";
  } catch (const ArmctlError& e) {
    EXPECT_NE(std::string(e.what()).find("FAKE0001"), std::string::npos) << e.what();
  }
}

TEST(HidOptions, ReadAttemptsOutsideRangeAreRefused) {
  FakeHidBackend fake;
  auto link = HidLink::open_board("", fake);
  auto o = hid_client_options();
  o.read_attempts = 0;
  EXPECT_THROW(Client(*link, o), ArmctlError);
  o.read_attempts = 11;
  EXPECT_THROW(Client(*link, o), ArmctlError);
}

}  // namespace
}  // namespace armctl::robot_commands

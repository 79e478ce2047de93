// The host SDK on simulated time: refusal before sending, reply matching, timeouts,
// notifications (and real-board variants) never lost, group download frame sequences, and
// every command against the emulated xArm.
#include <gtest/gtest.h>

#include "devices/robot_commands/client.hpp"
#include "sim_links.hpp"

namespace armctl::robot_commands {
namespace {

using namespace std::chrono_literals;
using testing::EmulatedLink;
using testing::ScriptedLink;
using Bytes = std::vector<std::uint8_t>;

Bytes wire(const rc::Frame& f) { return rc::encode_frame(f); }

// ------------------------------------------------------------------ refusal before sending

TEST(ClientRefuses, BadInputSendsNothing) {
  ScriptedLink link;
  Client c(link);
  EXPECT_EQ(c.move({{7, 500}}, 100).error().kind, ErrorKind::invalid_argument);
  EXPECT_FALSE(c.move({{1, 1001}}, 100));
  EXPECT_FALSE(c.move({{1, 500}}, 30001));
  EXPECT_FALSE(c.move({}, 100));
  EXPECT_FALSE(c.read_positions({0}));
  EXPECT_FALSE(c.servos_off({1, 1}));
  EXPECT_FALSE(c.read_offsets({8}));
  EXPECT_FALSE(c.adjust_offset(1, 200));
  EXPECT_FALSE(c.adjust_offset(1, -126));
  EXPECT_FALSE(c.save_offsets({}));
  EXPECT_FALSE(c.set_mode(9, ServoMode::motor, 100));
  // ServoSpeed: the board accepts a signed speed -1000..1000 only; the SDK refuses the rest.
  for (std::int16_t speed : {1001, -1001, 32767, -32768}) {
    auto refused = c.set_mode(1, ServoMode::motor, speed);
    ASSERT_FALSE(refused) << speed;
    EXPECT_EQ(refused.error().kind, ErrorKind::invalid_argument);
    EXPECT_NE(refused.error().message.find("ServoSpeed: speed " + std::to_string(speed)),
              std::string::npos) << refused.error().message;
    EXPECT_NE(refused.error().message.find("-1000..1000"), std::string::npos);
  }
  EXPECT_FALSE(c.set_mode(1, ServoMode::servo, 2000));
  EXPECT_FALSE(c.write_bus_servo_info(BusServoInfoWrite{1, 0, 1000, 4500, 12000, 40, 0, 0}));
  EXPECT_FALSE(c.download_group(1, {}));
  EXPECT_FALSE(c.download_group(1, std::vector<GroupAction>(1021, GroupAction{100, {{1, 5}}})));
  EXPECT_FALSE(c.download_group(1, {{100, {{1, 5}}}, {100, {{1, 5}, {2, 5}}}}));
  EXPECT_FALSE(c.download_group(255, {{100, {{1, 5}}}}));
  EXPECT_FALSE(c.run_group(255, 1));
  EXPECT_FALSE(c.set_group_speed(3, 0));
  EXPECT_TRUE(link.sent.empty());
  // A bad action deep in a group is named, and no frame of the download is sent.
  std::vector<GroupAction> actions(300, GroupAction{100, {{1, 500}}});
  actions[299].targets[0].position = 1200;
  auto s = c.download_group(1, actions);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("action 300"), std::string::npos) << s.error().message;
  EXPECT_TRUE(link.sent.empty());
}

TEST(ClientRefuses, ServoCountIsAPropertyOfTheClient) {
  ScriptedLink link;
  Client scara(link, ClientOptions{.servo_count = 7});
  EXPECT_TRUE(scara.move({{7, 500}}, 100));
  ASSERT_EQ(link.sent.size(), 1u);
  EXPECT_THROW(Client(link, ClientOptions{.servo_count = 0}), ArmctlError);
}

// --------------------------------------------------------------- replies and timeouts

TEST(ClientReplies, TimeoutIsBoundedOnSimulatedTime) {
  ScriptedLink link;  // never answers
  Client c(link, ClientOptions{.reply_timeout = 250ms});
  const auto start = link.sim_clock().now();
  auto r = c.battery_millivolts();
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::timeout);
  EXPECT_NE(r.error().message.find("GetBatteryVoltage"), std::string::npos);
  EXPECT_EQ(link.sim_clock().now() - start, 250ms);
}

TEST(ClientReplies, LateReplyTimesOutThenIsDiscardedAsStale) {
  ScriptedLink link([](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd == 15) return {{520ms, rc::Frame{15, {0x4C, 0x1D}}}};
    if (f.cmd == 21) return {{10ms, rc::Frame{21, {1, 1, 0xF4, 0x01}}}};
    return {};
  });
  Client c(link, ClientOptions{.reply_timeout = 500ms});
  EXPECT_EQ(c.battery_millivolts().error().kind, ErrorKind::timeout);
  // The late battery reply arrives while waiting for positions and is not taken for one.
  link.sim_clock().advance(50ms);
  auto p = c.read_positions({1});
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ((*p)[0].position, 500);
  EXPECT_EQ(c.stats().stale_replies, 1u);
}

TEST(ClientReplies, NotificationsBetweenRequestAndReplyAreNotLost) {
  ScriptedLink link([](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd != 15) return {};
    return {{1ms, rc::Frame{6, {2, 3, 0}}},
            {2ms, rc::Frame{0x63, {}}},  // unreadable: skipped and counted
            {3ms, rc::Frame{8, {2, 3, 0}}},
            {4ms, rc::Frame{15, {0x4C, 0x1D}}}};
  });
  Client c(link);
  std::vector<GroupEvent> seen;
  c.set_event_callback([&](const GroupEvent& e) { seen.push_back(e); });
  auto mv = c.battery_millivolts();
  ASSERT_TRUE(mv) << mv.error().message;
  EXPECT_EQ(*mv, 7500);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].kind, GroupEventKind::started);
  EXPECT_EQ(seen[0].group, 2);
  EXPECT_EQ(seen[0].count, 3);
  EXPECT_EQ(seen[1].kind, GroupEventKind::finished);
  EXPECT_FALSE(seen[1].variant);
  EXPECT_EQ(c.pending_events(), 2u);  // queued as well as called back
  EXPECT_EQ(c.stats().unreadable_frames, 1u);
}

TEST(ClientReplies, EraseReplyIsNotConfusedWithFinishedNotification) {
  ScriptedLink link([](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd != 8) return {};
    return {{1ms, rc::Frame{8, {1, 1, 0}}}, {2ms, rc::Frame{8, {}}}};
  });
  Client c(link);
  ASSERT_TRUE(c.erase_group(255));
  auto e = c.next_event();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->kind, GroupEventKind::finished);
  EXPECT_EQ(e->group, 1);
}

TEST(ClientReplies, MalformedReplyWithTheAwaitedCmdIsAProtocolError) {
  ScriptedLink link([](const rc::Frame&) -> std::vector<ScriptedLink::Timed> {
    return {{1ms, rc::Frame{21, {2, 1, 0xF4, 0x01}}}};  // count 2, one entry
  });
  Client c(link);
  auto r = c.read_positions({1, 2});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::protocol);
}

TEST(ClientReplies, AnswerForOtherServosIsAProtocolError) {
  ScriptedLink link([](const rc::Frame&) -> std::vector<ScriptedLink::Timed> {
    return {{1ms, rc::Frame{21, {1, 3, 0xF4, 0x01}}}};
  });
  Client c(link);
  auto r = c.read_positions({1});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("asked for servos 1"), std::string::npos);
}

// ------------------------------------------------------------ a read in two halves

// The servo mode's read-back on a full-duplex line: the request goes out, moves follow it
// while the reply comes back, and the reply is there when collected.
TEST(ClientSplitRead, MovesGoOutWhileTheRequestedReplyComesBack) {
  EmulatedLink link(115200);
  Client c(link);
  ASSERT_TRUE(c.move({{1, 300}}, 0));
  ASSERT_TRUE(c.pump_events(link.sim_clock().now() + 500ms));  // the board moves servo 1 there
  const TimePoint asked = link.sim_clock().now();
  ASSERT_TRUE(c.request_positions({1, 2}));
  EXPECT_TRUE(c.position_request_pending());
  EXPECT_EQ(link.sim_clock().now(), asked);  // nothing waited for
  ASSERT_TRUE(c.move({{2, 600}}, 20));
  ASSERT_TRUE(c.pump_events(asked + 1ms));  // receives meanwhile, as a servo loop's idle does
  ASSERT_TRUE(c.move({{2, 610}}, 20));
  auto p = c.collect_positions();
  ASSERT_TRUE(p) << p.error().message;
  ASSERT_EQ(p->size(), 2u);
  EXPECT_EQ((*p)[0].position, 300);
  EXPECT_FALSE(c.position_request_pending());
  // The reply's time on the wire: request (7 bytes) and reply (11 bytes) at 115200 baud; the
  // moves sent after the request did not delay it.
  EXPECT_LE(link.sim_clock().now() - asked, link.frame_time(7) + link.frame_time(11) + 1ms);
  EXPECT_EQ(c.stats().stale_replies, 0u);
  ASSERT_EQ(link.sent.size(), 4u);
  EXPECT_EQ(link.sent[1].cmd, 21);  // request, then the two moves
  EXPECT_EQ(link.sent[2].cmd, 3);
  // Nothing left in flight: collecting again is a caller's mistake, said so.
  auto again = c.collect_positions();
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error().kind, ErrorKind::invalid_argument);
}

// A reply that never comes: a timeout as for read_positions, or its retries when asked.
TEST(ClientSplitRead, AMissingReplyTimesOutOrIsReadAgain) {
  int requests = 0;
  ScriptedLink link([&](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd == 21 && ++requests >= 2) return {{5ms, rc::Frame{21, {1, 1, 0xF4, 0x01}}}};
    return {};
  });
  {
    Client c(link, ClientOptions{.reply_timeout = 100ms});
    const TimePoint asked = link.sim_clock().now();
    ASSERT_TRUE(c.request_positions({1}));
    auto p = c.collect_positions();
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().kind, ErrorKind::timeout);
    EXPECT_NE(p.error().message.find("ServoPositionRead"), std::string::npos) << p.error().message;
    EXPECT_EQ(link.sim_clock().now() - asked, 100ms);
    EXPECT_EQ(requests, 1);
  }
  requests = 0;
  Client c(link, ClientOptions{.reply_timeout = 100ms, .read_attempts = 2});
  ASSERT_TRUE(c.request_positions({1}));
  auto p = c.collect_positions();
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ((*p)[0].position, 500);
  EXPECT_EQ(requests, 2);
  EXPECT_EQ(c.stats().read_retries, 1u);
}

// A read while a request is in flight waits for that request's reply first, so the older
// reply is never taken for the newer read's.
TEST(ClientSplitRead, AReadAfterARequestIsNotAnsweredByTheRequestsReply) {
  std::uint8_t position = 100;
  ScriptedLink link([&](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd != 21) return {};
    const std::uint8_t now = position;
    position = std::uint8_t(position + 100);
    return {{3ms, rc::Frame{21, {1, 1, now, 0}}}};
  });
  Client c(link);
  ASSERT_TRUE(c.request_positions({1}));
  auto p = c.read_positions({1});
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ((*p)[0].position, 200);
  EXPECT_FALSE(c.position_request_pending());
  EXPECT_EQ(c.stats().stale_replies, 0u);
}

// -------------------------------------------------------------------- notifications

TEST(ClientEvents, RealBoardVariants) {
  ScriptedLink link;
  Client c(link);
  link.inject(rc::Frame{6, {}}, 1ms);   // started, no DATA
  link.inject(rc::Frame{7, {}}, 2ms);   // no GroupStop sent: this means finished
  ASSERT_TRUE(c.pump_events(link.sim_clock().now() + 10ms));
  auto a = c.next_event();
  auto b = c.next_event();
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->kind, GroupEventKind::started);
  EXPECT_TRUE(a->variant);
  EXPECT_FALSE(a->group);
  EXPECT_EQ(b->kind, GroupEventKind::finished);
  EXPECT_TRUE(b->variant);

  ASSERT_TRUE(c.stop_group());
  EXPECT_EQ(wire(link.sent.back()), (Bytes{0x55, 0x55, 0x02, 0x07}));
  link.inject(rc::Frame{7, {}}, 1ms);
  auto s = c.wait_event(link.sim_clock().now() + 10ms);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->kind, GroupEventKind::stopped);
  EXPECT_FALSE(s->variant);
  EXPECT_FALSE(c.wait_event(link.sim_clock().now() + 10ms));
}

// ------------------------------------------------------------ group download sequences

// The frames the spec's decisions require, built here byte by byte (not with the codec).
std::vector<Bytes> expected_download(std::uint8_t group, const std::vector<GroupAction>& actions) {
  std::vector<Bytes> out;
  const std::size_t n = actions.size();
  Bytes begin{0x55, 0x55, 0, 0x05, 0x01, group};
  for (std::size_t left = n; left > 0;) {
    const std::size_t b = std::min<std::size_t>(left, 255);
    begin.push_back(static_cast<std::uint8_t>(b));
    left -= b;
  }
  begin[2] = static_cast<std::uint8_t>(begin.size() - 2);
  out.push_back(begin);
  const auto servos = static_cast<std::uint8_t>(actions[0].targets.size());
  out.push_back({0x55, 0x55, 0x07, 0x05, 0x02, group, 0x00, servos, 0x00});
  Bytes blocks{0x55, 0x55, 0, 0x05, 0x03, group, 0x00};
  for (std::size_t b = 0; b * 255 < n; ++b) blocks.push_back(static_cast<std::uint8_t>(b));
  blocks[2] = static_cast<std::uint8_t>(blocks.size() - 2);
  out.push_back(blocks);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = actions[i];
    Bytes f{0x55, 0x55, 0, 0x05, 0x04, group, static_cast<std::uint8_t>(i / 255),
            static_cast<std::uint8_t>(i % 255), static_cast<std::uint8_t>(2 + 3 * servos),
            static_cast<std::uint8_t>(a.time_ms & 0xFF), static_cast<std::uint8_t>(a.time_ms >> 8)};
    for (const auto& t : a.targets) {
      const std::uint16_t p = t.position.value_or(0xFF00);
      f.insert(f.end(), {t.servo, static_cast<std::uint8_t>(p & 0xFF),
                         static_cast<std::uint8_t>(p >> 8)});
    }
    f[2] = static_cast<std::uint8_t>(f.size() - 2);
    out.push_back(f);
  }
  out.push_back({0x55, 0x55, 0x04, 0x05, 0x05, group});
  return out;
}

std::vector<GroupAction> make_actions(std::size_t n) {
  std::vector<GroupAction> actions;
  for (std::size_t i = 0; i < n; ++i) {
    actions.push_back({static_cast<std::uint16_t>(100 + i % 7),
                       {{1, static_cast<std::uint16_t>(i % 1001)},
                        {2, std::nullopt},
                        {6, static_cast<std::uint16_t>((i * 37) % 1001)}}});
  }
  return actions;
}

ScriptedLink::Responder auto_ack() {
  return [](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd == 5) return {{1ms, rc::Frame{5, {f.data[0], 0}}}};
    return {};
  };
}

class GroupDownloadSizes : public ::testing::TestWithParam<std::size_t> {};

TEST_P(GroupDownloadSizes, FrameSequenceMatchesTheSpecByteForByte) {
  const auto actions = make_actions(GetParam());
  ScriptedLink link(auto_ack());
  Client c(link);
  ASSERT_TRUE(c.download_group(4, actions));
  const auto expected = expected_download(4, actions);
  ASSERT_EQ(link.sent.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(wire(link.sent[i]), expected[i]) << "frame " << i;
  }
}

TEST_P(GroupDownloadSizes, EmulatedBoardStoresAndPlaysTheGroup) {
  const auto actions = make_actions(GetParam());
  EmulatedLink link;
  Client c(link, ClientOptions{.reply_timeout = 500ms, .download_timeout = 500ms});
  auto s = c.download_group(9, actions);
  ASSERT_TRUE(s) << s.error().message;
  const auto* stored = link.emulator().groups().find(9);
  ASSERT_NE(stored, nullptr);
  EXPECT_EQ(stored->actions.size(), actions.size());
  EXPECT_EQ(stored->servo_count, 3);
}

INSTANTIATE_TEST_SUITE_P(Sizes, GroupDownloadSizes, ::testing::Values(1, 255, 256, 1020));

TEST(GroupDownload, MissingAckStopsTheDownloadWithATimeout) {
  ScriptedLink link([](const rc::Frame& f) -> std::vector<ScriptedLink::Timed> {
    if (f.cmd == 5 && f.data[0] != 3) return {{1ms, rc::Frame{5, {f.data[0], 0}}}};
    return {};
  });
  Client c(link);
  auto s = c.download_group(1, make_actions(3));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::timeout);
  EXPECT_NE(s.error().message.find("sub 3"), std::string::npos) << s.error().message;
  EXPECT_EQ(link.sent.size(), 3u);  // nothing after the unanswered sub 3
}

// ------------------------------------------------------ every command, emulated xArm

TEST(ClientOnEmulator, EveryCommand) {
  EmulatedLink link;
  Client c(link);
  auto& servos = link.emulator().servos();

  ASSERT_TRUE(c.move({{1, 300}, {2, std::nullopt}, {6, 700}}, 1000));
  ASSERT_TRUE(c.pump_events(link.sim_clock().now() + 1100ms));
  auto pos = c.read_all_positions();
  ASSERT_TRUE(pos) << pos.error().message;
  ASSERT_EQ(pos->size(), 6u);
  EXPECT_EQ((*pos)[0].position, 300);
  EXPECT_EQ((*pos)[1].position, 500);  // left alone
  EXPECT_EQ((*pos)[5].position, 700);

  ASSERT_TRUE(c.servos_off({1, 6}));
  ASSERT_TRUE(c.pump_events(link.sim_clock().now() + 1ms));
  EXPECT_FALSE(servos.torque(1));
  EXPECT_TRUE(servos.torque(2));

  auto mv = c.battery_millivolts();
  ASSERT_TRUE(mv) << mv.error().message;
  EXPECT_GT(*mv, 6000);

  ASSERT_TRUE(c.adjust_offset(3, -20));
  auto off = c.read_offsets({3, 4});
  ASSERT_TRUE(off) << off.error().message;
  EXPECT_EQ((*off)[0].offset, -20);
  EXPECT_EQ((*off)[1].offset, 0);
  ASSERT_TRUE(c.save_offsets({3}));
  ASSERT_TRUE(c.pump_events(link.sim_clock().now() + 1ms));
  EXPECT_EQ(servos.saved_offset(3), -20);

  ASSERT_TRUE(c.set_mode(2, ServoMode::motor, 500));
  ASSERT_TRUE(c.pump_events(link.sim_clock().now() + 1ms));
  EXPECT_EQ(servos.mode(2), rc_board::ServoMode::motor);
  // Full speed in reverse travels as two's complement (-1000 = FC18) and the board obeys it.
  ASSERT_TRUE(c.set_mode(5, ServoMode::motor, -1000));
  EXPECT_EQ(link.sent.back().data, (std::vector<std::uint8_t>{5, 1, 0x18, 0xFC}));
  const double before = servos.commanded_position(5);
  ASSERT_TRUE(c.pump_events(link.sim_clock().now() + 100ms));
  EXPECT_EQ(servos.mode(5), rc_board::ServoMode::motor);
  EXPECT_NEAR(servos.commanded_position(5), before - 150.0, 2.0);  // 1.5 units/s per speed unit

  auto info = c.read_bus_servo_info();
  ASSERT_TRUE(info) << info.error().message;
  ASSERT_TRUE(c.write_bus_servo_info(BusServoInfoWrite{1, 100, 900, 5000, 11000, 80, 0, 7}));
  auto info2 = c.read_bus_servo_info();
  ASSERT_TRUE(info2) << info2.error().message;
  EXPECT_EQ(info2->position_min, 100);
  EXPECT_EQ(info2->temp_max, 80);
  EXPECT_EQ(info2->led_warning, 7);

  // Groups: download, speed, run twice, started then finished events.
  ASSERT_TRUE(c.download_group(2, {{200, {{1, 400}, {6, 600}}}, {200, {{1, 600}, {6, 400}}}}));
  ASSERT_TRUE(c.set_group_speed(2, 200));
  ASSERT_TRUE(c.run_group(2, 2));
  auto started = c.wait_event(link.sim_clock().now() + 100ms);
  ASSERT_TRUE(started);
  EXPECT_EQ(started->kind, GroupEventKind::started);
  EXPECT_EQ(started->group, 2);
  EXPECT_EQ(started->count, 2);
  const auto t0 = link.sim_clock().now();
  auto finished = c.wait_event(t0 + 5s);
  ASSERT_TRUE(finished);
  EXPECT_EQ(finished->kind, GroupEventKind::finished);
  EXPECT_EQ(finished->group, 2);
  // 4 actions of 200 ms at 200 % speed: clearly less than the 800 ms they take at 100 %
  // (the emulator adds its own settling per run, so not exactly 400 ms).
  EXPECT_GE(link.sim_clock().now() - t0, 350ms);
  EXPECT_LT(link.sim_clock().now() - t0, 700ms);

  // Continuous run, then stop.
  ASSERT_TRUE(c.run_group(2, 0));
  ASSERT_TRUE(c.wait_event(link.sim_clock().now() + 100ms));
  link.sim_clock().advance(1s);
  ASSERT_TRUE(c.stop_group());
  auto stopped = c.wait_event(link.sim_clock().now() + 100ms);
  ASSERT_TRUE(stopped);
  EXPECT_EQ(stopped->kind, GroupEventKind::stopped);

  ASSERT_TRUE(c.erase_group(2));
  EXPECT_EQ(link.emulator().groups().find(2), nullptr);
  ASSERT_TRUE(c.erase_group(255));
  EXPECT_EQ(link.emulator().board().stats().ignored(), 0u);
}

}  // namespace
}  // namespace armctl::robot_commands

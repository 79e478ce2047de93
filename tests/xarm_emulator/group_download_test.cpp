// GroupDownload sub 1..5 per the spec's decisions, and GroupRun/Stop/Erase/Speed with every
// notification, against the emulated xArm on a SimClock.
#include "harness.hpp"

#include "devices/rc_board/group_player.hpp"

namespace armctl::xarm::test {
namespace {

// Action i of a test group: servo 1 to a position that identifies it.
std::uint16_t position_for(std::size_t i, std::size_t salt = 0) {
  return static_cast<std::uint16_t>((i * 7 + salt * 13) % 1001);
}

// Frames of a complete download of `count` actions of `servos` servos.
std::vector<rc::Request> download(std::uint8_t group, std::size_t count, std::size_t servos = 3,
                                  std::size_t salt = 0, std::uint16_t ms = 100) {
  std::vector<rc::Request> r;
  r.push_back(rc::GroupDownloadBegin{group, static_cast<std::uint16_t>(count)});
  r.push_back(rc::GroupDownloadServoCount{group, static_cast<std::uint8_t>(servos)});
  r.push_back(rc::GroupDownloadBlocks{group, rc::blocks_for_actions(static_cast<int>(count))});
  for (std::size_t i = 0; i < count; ++i) {
    rc::GroupDownloadAction a{
        group, static_cast<std::uint8_t>(i / 255), static_cast<std::uint8_t>(i % 255), ms, {}};
    for (std::size_t s = 0; s < servos; ++s)
      a.targets.push_back({static_cast<std::uint8_t>(s + 1), position_for(i + s, salt)});
    r.push_back(a);
  }
  r.push_back(rc::GroupDownloadEnd{group});
  return r;
}

void send_all(Emulated& e, const std::vector<rc::Request>& requests) {
  for (const auto& r : requests) e.send_unchecked(r);
}

std::size_t acks(const Emulated& e) {
  std::size_t n = 0;
  for (const auto& f : e.out) n += f.cmd == 5 ? 1 : 0;
  return n;
}

void expect_group(const Emulated& e, std::uint8_t group, std::size_t count, std::size_t servos,
                  std::size_t salt) {
  const auto* g = e.emulator.board().store().find(group);
  ASSERT_NE(g, nullptr);
  ASSERT_EQ(g->actions.size(), count);
  EXPECT_EQ(g->servo_count, servos);
  for (std::size_t i = 0; i < count; ++i) {
    ASSERT_EQ(g->actions[i].positions.size(), servos);
    EXPECT_EQ(g->actions[i].positions[0].position, position_for(i, salt)) << "action " << i;
  }
}

class Downloads : public ::testing::TestWithParam<std::size_t> {};

TEST_P(Downloads, CompleteDownloadIsStoredAndEveryFrameAcknowledged) {
  const std::size_t count = GetParam();
  Emulated e;
  auto requests = download(7, count);
  send_all(e, requests);
  EXPECT_EQ(acks(e), requests.size());
  EXPECT_EQ(e.stats().ignored(), 0u);
  expect_group(e, 7, count, 3, 0);
  EXPECT_FALSE(e.emulator.board().download_in_progress());
}

INSTANTIATE_TEST_SUITE_P(Counts, Downloads, ::testing::Values(1, 255, 256, 1020));

TEST(GroupDownload, VectorFramesAreAcknowledgedByteExactly) {
  Emulated e;
  for (auto name :
       {"GroupDownload begin group 4, 300 actions", "GroupDownload servos per action = 3",
        "GroupDownload blocks 0 and 1 (<= 510 actions)",
        "GroupDownload action block 0 index 7, 800 ms, 3 servos"})
    e.send(vector_bytes(name));
  ASSERT_EQ(e.out.size(), 4u);
  EXPECT_EQ(to_hex(rc::encode_frame(e.out[0])), to_hex(vector_bytes("GroupDownload ack of sub 1")));
  EXPECT_EQ(e.out[3].data, (std::vector<std::uint8_t>{4, 0}));
  // Only one of 300 actions arrived: sub 5 is a count mismatch, nothing is stored.
  e.send(vector_bytes("GroupDownload end group 4"));
  EXPECT_EQ(e.out.size(), 4u);
  EXPECT_EQ(e.stats().download_rejected, 1u);
  EXPECT_EQ(e.emulator.board().store().find(4), nullptr);
  EXPECT_NE(e.emulator.board().last_rejection().find("1 of 300"), std::string::npos)
      << e.emulator.board().last_rejection();
}

TEST(GroupDownload, AbandonedDownloadLeavesOldGroupIntact) {
  Emulated e;
  send_all(e, download(2, 10, 3, /*salt=*/1));
  expect_group(e, 2, 10, 3, 1);
  auto second = download(2, 20, 3, /*salt=*/2);
  second.pop_back();  // no sub 5
  send_all(e, second);
  expect_group(e, 2, 10, 3, 1);  // old content
  // A new download of another group abandons the unfinished one for good.
  send_all(e, download(3, 5));
  e.send(rc::GroupDownloadEnd{2});
  expect_group(e, 2, 10, 3, 1);
  EXPECT_EQ(e.stats().download_rejected, 1u);
}

struct Inconsistent {
  const char* name;
  std::function<void(std::vector<rc::Request>&)> spoil;  // applied to a 300-action download
  std::vector<std::uint8_t> raw;                         // or a raw frame sent before sub 5
};

TEST(GroupDownload, InconsistentDownloadsAreRejectedAndOldGroupKept) {
  std::vector<Inconsistent> cases = {
      {"index outside its block (block 1 index 45 = action 300 of 300)",
       [](auto& r) {
         std::get<rc::GroupDownloadAction>(r[5]).index = 45,
         std::get<rc::GroupDownloadAction>(r[5]).block = 1;
       },
       {}},
      {"block beyond those announced",
       [](auto& r) { std::get<rc::GroupDownloadAction>(r[5]).block = 2; },
       {}},
      {"count mismatch at sub 5 (an action missing)", [](auto& r) { r.erase(r.begin() + 10); }, {}},
      {"blocks disagree with the count",
       [](auto& r) { std::get<rc::GroupDownloadBlocks>(r[2]).block_count = 1; },
       {}},
      {"servo count above the arm's",
       [](auto& r) { std::get<rc::GroupDownloadServoCount>(r[1]).servo_count = 7; },
       {}},
      {"action with a different servo count",
       [](auto& r) { std::get<rc::GroupDownloadAction>(r[8]).targets.pop_back(); },
       {}},
      {"sub 4 before sub 3", [](auto& r) { std::swap(r[2], r[3]); }, {}},
      {"sub for another group",
       [](auto& r) { std::get<rc::GroupDownloadAction>(r[9]).group = 6; },
       {}},
      {"byte count disagreeing with n", nullptr,
       hex("04 05 00 09 0B 20 03 01 90 01 02 F4 01 03 58")},
      {"byte count not 2 + 3n", nullptr, hex("04 05 00 09 0A 20 03 01 90 01 02 F4 01 03 58")},
      {"servo not present", nullptr, hex("04 05 00 09 0B 20 03 01 90 01 02 F4 01 09 58 02")},
      {"position out of range", nullptr, hex("04 05 00 09 0B 20 03 01 90 01 02 F4 01 03 E9 03")},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    Emulated e;
    send_all(e, download(5, 3, 3, /*salt=*/4));
    auto spoiled = download(5, 300, 3, /*salt=*/9);
    if (c.spoil) {
      c.spoil(spoiled);
      send_all(e, spoiled);
    } else {
      spoiled.pop_back();
      send_all(e, spoiled);
      e.send_raw(5, c.raw);
      e.send(rc::GroupDownloadEnd{5});
    }
    EXPECT_GE(e.stats().download_rejected, 1u);
    expect_group(e, 5, 3, 3, 4);  // the old group, untouched
    EXPECT_FALSE(e.emulator.board().download_in_progress());
  }
}

TEST(GroupDownload, RetransmittedActionOverwritesItsSlot) {
  Emulated e;
  auto r = download(1, 3);
  r.insert(r.begin() + 4, r[4]);  // action 1 twice
  send_all(e, r);
  expect_group(e, 1, 3, 3, 0);
}

// ---------------------------------------------------------------- playback

void store_group(Emulated& e, std::uint8_t group,
                 std::vector<std::pair<std::uint16_t, std::uint16_t>> ms_pos) {
  std::vector<rc::Request> r;
  r.push_back(rc::GroupDownloadBegin{group, static_cast<std::uint16_t>(ms_pos.size())});
  r.push_back(rc::GroupDownloadServoCount{group, 2});
  r.push_back(rc::GroupDownloadBlocks{group, 1});
  for (std::size_t i = 0; i < ms_pos.size(); ++i)
    r.push_back(rc::GroupDownloadAction{group,
                                        0,
                                        static_cast<std::uint8_t>(i),
                                        ms_pos[i].first,
                                        {{1, ms_pos[i].second}, {2, std::nullopt}}});
  r.push_back(rc::GroupDownloadEnd{group});
  send_all(e, r);
  e.out.clear();
}

TEST(GroupRun, PlaysActionsTimedAndNotifiesStartedAndFinishedLikeTheVectors) {
  Emulated e;
  store_group(e, 2, {{1000, 600}, {500, 400}});
  e.send(vector_bytes("GroupRun group 2, 3 times"));
  ASSERT_EQ(e.out.size(), 1u);
  EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("notification: group 2 started, 3 times")));
  for (int pass = 0; pass < 3; ++pass) {
    e.advance_ms(500);
    EXPECT_NEAR(e.position(1), pass == 0 ? 550 : 500, 1) << pass;  // first action halfway
    e.advance_ms(500);
    EXPECT_EQ(e.position(1), 600);
    e.advance_ms(250);
    EXPECT_EQ(e.position(1), 500);  // second action halfway
    EXPECT_EQ(e.position(2), 500);  // "keep" servo never moved
    if (pass < 2) {
      e.advance_ms(250);
      EXPECT_TRUE(e.out.empty());
    }
  }
  e.advance_ms(249);
  EXPECT_TRUE(e.out.empty());
  e.advance_ms(1);
  EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("notification: group 2 finished")));
  EXPECT_EQ(e.position(1), 400);
  EXPECT_FALSE(e.emulator.board().running_group());
}

TEST(GroupRun, OneBigClockJumpStillPlaysEveryActionAtItsInstant) {
  Emulated e;
  store_group(e, 1, {{100, 600}, {100, 700}, {100, 800}});
  e.send(rc::GroupRun{1, 2});
  e.advance_ms(10000);
  EXPECT_EQ(e.position(1), 800);
  ASSERT_EQ(e.out.size(), 2u);
  EXPECT_EQ(e.out[1].cmd, 8);
  EXPECT_EQ(e.emulator.servos().commanded_position(1), 800);
}

TEST(GroupRun, SpeedScalesTimeTwoHundredPercentIsTwiceAsFast) {
  Emulated e;
  store_group(e, 1, {{1000, 700}});
  e.send(vector_bytes("GroupSpeed group 1 at 200 %"));
  EXPECT_EQ(e.emulator.board().group_speed(1), 200);
  e.send(rc::GroupRun{1, 1});
  e.advance_ms(250);
  EXPECT_EQ(e.position(1), 600);  // halfway after 250 of 500 ms
  e.advance_ms(250);
  ASSERT_EQ(e.out.size(), 2u);  // started, finished after 500 ms
  EXPECT_EQ(e.out[1].cmd, 8);
  EXPECT_EQ(rc_board::scaled_time(1000, 50), std::chrono::milliseconds(2000));
}

TEST(GroupRun, SpeedForAllGroups) {
  Emulated e;
  e.send(rc::GroupSpeed{255, 50});
  EXPECT_EQ(e.emulator.board().group_speed(0), 50);
  EXPECT_EQ(e.emulator.board().group_speed(254), 50);
  e.send_raw(11, hex("01 00 00"));  // 0 % would never finish: ignored
  EXPECT_EQ(e.emulator.board().group_speed(1), 50);
  EXPECT_EQ(e.stats().ignored(), 1u);
}

TEST(GroupRun, ContinuousUntilStopHaltsWhereItIs) {
  Emulated e;
  store_group(e, 0, {{1000, 1000}, {1000, 0}});
  e.send(vector_bytes("GroupRun group 0, continuous"));
  e.advance_ms(60 * 1000 + 500);  // 30 passes and half an action: still running
  EXPECT_EQ(to_hex(e.take_bytes()), "55 55 05 06 00 00 00");  // started only
  EXPECT_EQ(e.position(1), 500);                              // 0 -> 1000, halfway
  e.send(vector_bytes("GroupStop"));
  EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("notification: stopped")));
  e.advance_ms(2000);
  EXPECT_EQ(e.position(1), 500);  // halted where it was
  EXPECT_TRUE(e.out.empty());     // no finished after a stop
  EXPECT_FALSE(e.emulator.board().running_group());
}

TEST(GroupRun, EmptyGroupIsRefusedWithoutNotification) {
  Emulated e;
  e.send(rc::GroupRun{9, 1});
  EXPECT_TRUE(e.out.empty());
  EXPECT_EQ(e.stats().refused, 1u);
}

TEST(GroupRun, NewRunReplacesRunningOneWithStoppedThenStarted) {
  Emulated e;
  store_group(e, 1, {{1000, 900}});
  store_group(e, 2, {{1000, 100}});
  e.send(rc::GroupRun{1, 0});
  e.advance_ms(100);
  e.send(rc::GroupRun{2, 1});
  ASSERT_EQ(e.out.size(), 3u);
  EXPECT_EQ(e.out[1].cmd, 7);
  EXPECT_EQ(e.out[2], (rc::Frame{6, {2, 1, 0}}));
}

TEST(GroupErase, OneOrAllWithEmptyReplyAndStopsTheRunningGroup) {
  Emulated e;
  store_group(e, 1, {{1000, 900}});
  store_group(e, 2, {{1000, 100}});
  store_group(e, 3, {{1000, 100}});
  e.send(rc::GroupErase{1});
  EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("GroupErase reply")));
  EXPECT_EQ(e.emulator.board().store().find(1), nullptr);
  EXPECT_NE(e.emulator.board().store().find(2), nullptr);
  e.send(rc::GroupRun{2, 0});
  e.out.clear();
  e.send(vector_bytes("GroupErase all"));
  ASSERT_EQ(e.out.size(), 2u);
  EXPECT_EQ(e.out[0], (rc::Frame{7, {}}));  // the running group stopped
  EXPECT_EQ(e.out[1], (rc::Frame{8, {}}));
  EXPECT_EQ(e.emulator.board().store().size(), 0u);
  EXPECT_FALSE(e.emulator.board().running_group());
}

TEST(GroupRun, ActionsOutsideLimitsSetAfterDownloadAreSkippedWhole) {
  Emulated e;
  store_group(e, 1, {{100, 900}, {100, 300}});
  e.send(rc::BusServoInfoWrite{1, 0, 800, 4500, 12000, 85, 0, 0});
  e.send(rc::GroupRun{1, 1});
  e.advance_ms(1000);
  EXPECT_EQ(e.position(1), 300);
  EXPECT_EQ(e.emulator.board().group_actions_skipped(), 1u);
}

}  // namespace
}  // namespace armctl::xarm::test

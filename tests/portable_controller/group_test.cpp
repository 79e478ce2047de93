// Action groups in the portable core: download (sub 1..5) into a GroupStore over a
// byte-addressed memory, capacity, atomic replacement across resets, playback.
#include <gtest/gtest.h>

#include <vector>

#include "memory_rig.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/rc_codes.hpp"
#include "portable_controller/scara_arm.hpp"

namespace armctl::controller::testing {
namespace {

namespace jb = joint_bus;

std::vector<Action> wave(int n, int servos = 3) {
  std::vector<Action> out;
  for (int i = 0; i < n; ++i) {
    Action a{static_cast<std::uint16_t>(100 + i), {}};
    for (int s = 1; s <= servos; ++s) a.targets.push_back({s, 300 + (i * 37 + s * 11) % 400});
    out.push_back(a);
  }
  return out;
}

// What the store holds for `group`, as actions (empty if nothing).
std::vector<Action> stored(RamMemory& memory, std::uint8_t group) {
  GroupStore store;
  GroupStore::Entry directory[GroupStore::mega_entries];
  store.begin(&memory, 0, directory, GroupStore::mega_entries);
  GroupInfo info;
  std::vector<Action> out;
  if (!store.find(group, &info)) return out;
  for (std::uint16_t i = 0; i < info.action_count; ++i) {
    std::uint16_t ms;
    std::uint8_t servos[7];
    std::uint16_t positions[7];
    store.read_action(info, i, &ms, servos, positions);
    Action a{ms, {}};
    for (int k = 0; k < info.servo_count; ++k) a.targets.push_back({servos[k], positions[k]});
    out.push_back(a);
  }
  return out;
}

bool same(const std::vector<Action>& a, const std::vector<Action>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].ms != b[i].ms || a[i].targets != b[i].targets) return false;
  return true;
}

TEST(Groups, DownloadIsAcknowledgedAndStored) {
  RamMemory memory;
  GroupRig rig(memory);
  const auto actions = wave(300);  // two blocks
  ASSERT_TRUE(rig.download(7, actions));
  EXPECT_TRUE(same(stored(memory, 7), actions));
  EXPECT_EQ(rig.core.stats().downloads, 1);
}

TEST(Groups, InconsistentSubAbandonsTheDownloadWithoutReply) {
  RamMemory memory;
  GroupRig rig(memory);
  ASSERT_TRUE(rig.download(2, wave(3)));
  rig.upstream.frames.clear();
  rig.send(rc_group_download, {1, 2, 3});
  rig.send(rc_group_download, {2, 2, 0, 3, 0});
  rig.send(rc_group_download, {3, 2, 0, 0});
  rig.send(rc_group_download, {4, 2, 0, 5, 11, 100, 0, 1, 0x2C, 1, 2, 0x2C, 1, 3, 0x2C, 1});  // index 5 >= 3
  EXPECT_EQ(rig.acks(), 3u) << "no reply to the bad action";
  rig.send(rc_group_download, {5, 2});
  EXPECT_EQ(rig.acks(), 3u) << "the download was abandoned";
  EXPECT_TRUE(same(stored(memory, 2), wave(3))) << "the old content is intact";
  EXPECT_GE(rig.core.stats().download_rejected, 2);
}

TEST(Groups, ADownloadThatDoesNotFitIsRefusedAtTheServoCount) {
  RamMemory memory;
  GroupRig rig(memory);
  // 4096 - 132 - 96 (the servo settings) bytes of group data: 168 actions of 7 joints (23
  // bytes each).
  EXPECT_EQ(rig.core.groups().capacity_bytes() / GroupStore::action_bytes(7), 168);
  ASSERT_TRUE(rig.download(1, wave(166, 7)));
  rig.upstream.frames.clear();
  rig.send(rc_group_download, {1, 3, 5});
  rig.send(rc_group_download, {2, 3, 0, 7, 0});  // 5 x 23 bytes: only 2 actions' room left
  EXPECT_EQ(rig.acks(), 1u);
  EXPECT_EQ(rig.core.stats().download_too_big, 1);
  EXPECT_TRUE(same(stored(memory, 1), wave(166, 7)));
  EXPECT_TRUE(stored(memory, 3).empty());
  ASSERT_TRUE(rig.download(3, wave(2, 7))) << "what fits is taken";
}

TEST(Groups, ReplacementSurvivesAResetAfterAnyWrite) {
  // Download group 4 (old), then a replacement (new) that dies after `k` byte writes, for
  // every k: after the restart group 4 is exactly old or exactly new, never a mixture.
  const auto old_actions = wave(5);
  const auto new_actions = wave(4, 2);
  long total = 0;
  {
    RamMemory memory;
    GroupRig rig(memory);
    ASSERT_TRUE(rig.download(4, old_actions));
    const long before = memory.writes;
    ASSERT_TRUE(rig.download(4, new_actions));
    total = memory.writes - before;
  }
  ASSERT_GT(total, 30);
  int saw_old = 0, saw_new = 0;
  for (long k = 0; k <= total; ++k) {
    RamMemory memory;
    {
      GroupRig rig(memory);
      ASSERT_TRUE(rig.download(4, old_actions));
      memory.writes_left = k;
      rig.download(4, new_actions);
    }
    memory.writes_left = -1;
    GroupRig after(memory);  // restart: begin() repairs, then writes settle
    after.run_us(10000);
    const auto now_stored = stored(memory, 4);
    const bool is_old = same(now_stored, old_actions), is_new = same(now_stored, new_actions);
    EXPECT_TRUE(is_old || is_new) << "after " << k << " of " << total << " writes";
    saw_old += is_old;
    saw_new += is_new;
  }
  EXPECT_GT(saw_old, 0);
  EXPECT_GT(saw_new, 0);
}

TEST(Groups, RunPlaysEachActionAsAMoveAndNotifies) {
  RamMemory memory;
  GroupRig rig(memory);
  const std::vector<Action> actions{{200, {{1, 520}, {2, 480}}}, {200, {{1, 540}, {2, 460}}}};
  ASSERT_TRUE(rig.download(9, actions));
  rig.upstream.frames.clear();
  rig.send(rc_group_run, {9, 2, 0});
  rig.run_us(3000000);
  ASSERT_FALSE(rig.upstream.frames.empty());
  EXPECT_EQ(rig.upstream.frames.front().command, rc_group_run);
  EXPECT_EQ(rig.upstream.frames.front().data, (std::vector<std::uint8_t>{9, 2, 0}));
  EXPECT_EQ(rig.upstream.frames.back().command, rc_group_erase) << "CMD 8: finished";
  EXPECT_EQ(rig.upstream.frames.back().data, (std::vector<std::uint8_t>{9, 2, 0}));
  const auto drives = rig.joints.commands_of(jb::cmd_drive_to);
  ASSERT_EQ(drives.size(), 8u) << "2 actions x 2 joints x 2 passes";
  EXPECT_EQ(rig.core.stats().actions_played, 4);
  EXPECT_FALSE(rig.core.playing());
}

TEST(Groups, AJointThatStallsStopsThePlaybackWithCmd7) {
  // A stall mid-action stops the move (ControllerCore::check_ramp), and with it the group:
  // the host gets CMD 7, no further action is played.
  RamMemory memory;
  GroupRig rig(memory);
  ASSERT_TRUE(rig.download(2, {{1000, {{1, 600}, {2, 600}}}, {1000, {{1, 400}, {2, 400}}}}));
  rig.joints.stuck[1] = true;
  rig.upstream.frames.clear();
  rig.send(rc_group_run, {2, 1, 0});
  rig.run_us(3000000);
  ASSERT_GE(rig.upstream.frames.size(), 2u);
  EXPECT_EQ(rig.upstream.frames.front().command, rc_group_run) << "started";
  EXPECT_EQ(rig.upstream.frames.back().command, rc_group_stop) << "CMD 7: stopped";
  EXPECT_TRUE(rig.upstream.frames.back().data.empty());
  EXPECT_FALSE(rig.core.playing());
  EXPECT_EQ(rig.core.stats().stalls, 1);
  EXPECT_EQ(rig.core.stats().actions_played, 1) << "the second action never started";
}

TEST(Groups, SpeedScalesTheActionTime) {
  RamMemory memory;
  GroupRig rig(memory);
  ASSERT_TRUE(rig.download(1, {{2000, {{1, 520}}}}));
  rig.send(rc_group_speed, {1, 200, 0});
  rig.send(rc_group_run, {1, 1, 0});
  EXPECT_EQ(rig.core.planned_ms(), 1000u) << "200 % = twice as fast";
  rig.send(rc_group_speed, {1, 0, 0});  // 0 % is refused
  rig.send(rc_group_speed, {255, 50, 0});
  rig.send(rc_group_run, {1, 1, 0});
  EXPECT_EQ(rig.core.planned_ms(), 4000u);
}

TEST(Groups, StopAndEraseEndThePlayback) {
  RamMemory memory;
  GroupRig rig(memory);
  ASSERT_TRUE(rig.download(1, wave(3)));
  rig.send(rc_group_run, {1, 0, 0});  // until stopped
  rig.run_us(500000);
  EXPECT_TRUE(rig.core.playing());
  rig.upstream.frames.clear();
  rig.send(rc_group_stop, {});
  EXPECT_FALSE(rig.core.playing());
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  EXPECT_EQ(rig.upstream.frames[0].command, rc_group_stop);
  rig.send(rc_group_run, {1, 0, 0});
  rig.upstream.frames.clear();
  rig.send(rc_group_erase, {255});
  rig.run_us(10000);
  ASSERT_EQ(rig.upstream.frames.size(), 2u);
  EXPECT_EQ(rig.upstream.frames[0].command, rc_group_stop);
  EXPECT_EQ(rig.upstream.frames[1].command, rc_group_erase);
  EXPECT_TRUE(rig.upstream.frames[1].data.empty());
  EXPECT_TRUE(stored(memory, 1).empty());
  rig.send(rc_group_run, {1, 1, 0});
  EXPECT_FALSE(rig.core.playing()) << "an erased group does not run";
}

// Linux (CoreDevice) gives the store a memory of megabytes and a directory of 255 entries:
// a group stored above 64 KiB keeps its 24-bit start across a restart. An entry's third
// start byte that is 0xFF (the Mega's images before it was written) reads as 0.
TEST(GroupStoreLayout, ABigMemoryKeepsStartsAbove64KiB) {
  RamMemory memory(200000);
  std::vector<GroupStore::Entry> directory(255);
  GroupStore store;
  store.begin(&memory, 0, directory.data(), 255);
  while (!store.idle()) store.service();
  EXPECT_EQ(store.data_at(), 4u + 8u * 255u);
  const std::uint8_t action[5] = {0x2C, 0x01, 3, 0xF4, 0x01};  // 300 ms, servo 3 at 500
  const std::uint32_t start = 70000;
  ASSERT_TRUE(store.write(start, action, sizeof action));
  ASSERT_TRUE(store.commit(GroupInfo{200, 1, 1, start}));
  while (!store.idle()) store.service();

  GroupStore again;
  std::vector<GroupStore::Entry> directory2(255);
  again.begin(&memory, 0, directory2.data(), 255);
  GroupInfo info{};
  ASSERT_TRUE(again.find(200, &info));
  EXPECT_EQ(info.start, start);
  std::uint16_t ms = 0;
  std::uint8_t servos[7];
  std::uint16_t positions[7];
  ASSERT_TRUE(again.read_action(info, 0, &ms, servos, positions));
  EXPECT_EQ(ms, 300);
  EXPECT_EQ(servos[0], 3);
  EXPECT_EQ(positions[0], 500);

  // The entry as an image that left its eighth byte erased would have written it.
  for (std::uint32_t at = GroupStore::directory_at; at < store.data_at(); at += 8)
    if (memory.bytes[at] == 200) memory.bytes[at + 7] = 0xFF;
  GroupStore old;
  std::vector<GroupStore::Entry> directory3(255);
  old.begin(&memory, 0, directory3.data(), 255);
  ASSERT_TRUE(old.find(200, &info));
  EXPECT_EQ(info.start, start & 0xFFFFu);
}

}  // namespace
}  // namespace armctl::controller::testing

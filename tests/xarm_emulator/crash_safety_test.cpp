// kill -9 at varied instants while groups are being stored or downloaded: every group must
// load intact, old or new. The parent synchronises on pipe messages from the child (no
// sleeps): it kills after the child reports k events, k varied per trial, plus a varied
// spin so the kill also lands between reports.
#include "harness.hpp"

#include <unistd.h>

#include <iostream>

#include "core/atomic_file.hpp"
#include "devices/rc_board/group_store.hpp"
#include "support/killed_child.hpp"

namespace armctl::xarm::test {
namespace {

using rc_board::ActionGroup;
using rc_board::GroupStore;
using armctl::testing::kill_after_reports;
using armctl::testing::kill_and_reap;
using armctl::testing::read_u32;
using armctl::testing::spin;
using armctl::testing::write_u32;

// Version v of group g: large enough that a write takes a while; v is in every action's time.
ActionGroup version(std::uint8_t g, std::uint16_t v) {
  ActionGroup group{6, {}};
  std::size_t count = 100 + (v * 37u + g) % 900;
  for (std::size_t i = 0; i < count; ++i) {
    rc_board::Action a{v, {}};
    for (std::uint8_t s = 1; s <= 6; ++s)
      a.positions.push_back({s, static_cast<std::uint16_t>((v + i * s + g) % 1001)});
    group.actions.push_back(std::move(a));
  }
  return group;
}

std::optional<std::uint16_t> version_of(const ActionGroup* group, std::uint8_t g) {
  if (!group || group->actions.empty()) return std::nullopt;
  std::uint16_t v = group->actions[0].milliseconds;
  if (!(*group == version(g, v))) return std::nullopt;
  return v;
}

constexpr std::uint8_t kGroups = 3;

TEST(CrashSafety, KillDuringStoreWritesNeverLosesOrCorruptsAGroup) {
  TempDir dir;
  std::uint16_t acked[kGroups] = {0, 0, 0};  // newest version each group reported stored
  std::size_t torn = 0;                      // kills that landed inside a save
  for (unsigned trial = 0; trial < 24; ++trial) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {  // child: store new versions of every group in a loop until killed
      ::close(fds[0]);
      GroupStore store(dir.path());
      std::uint16_t v = 1;
      for (std::uint8_t g = 0; g < kGroups; ++g)
        if (auto have = version_of(store.find(g), g)) v = std::max<std::uint16_t>(v, *have + 1);
      for (;; ++v)
        for (std::uint8_t g = 0; g < kGroups; ++g) {
          if (!store.save(g, version(g, v)).ok()) ::_exit(3);
          write_u32(fds[1], std::uint32_t{g} << 16 | v);
        }
    }
    ::close(fds[1]);
    ASSERT_TRUE(kill_after_reports(fds[0], pid, 1 + (trial * 5) % 9, trial * 20000, acked))
        << "trial " << trial << ": the child ended";

    GroupStore store(dir.path());
    torn += store.problems().size();
    for (const auto& p : store.problems())
      EXPECT_NE(p.find("unfinished save"), std::string::npos) << "trial " << trial << ": " << p;
    for (std::uint8_t g = 0; g < kGroups; ++g) {
      if (acked[g] == 0) continue;  // never stored: absent or the first version, both fine
      auto v = version_of(store.find(g), g);
      ASSERT_TRUE(v.has_value()) << "trial " << trial << " group " << int(g) << " corrupt or lost";
      EXPECT_GE(*v, acked[g]) << "trial " << trial << " group " << int(g) << " went back";
      EXPECT_LE(*v, acked[g] + 1) << "trial " << trial;
    }
  }
  std::cout << "kills inside a save (temporary file left behind): " << torn << " of 24\n";
}

// Frames of a complete download of group 1, version v (v in the time of every action).
std::vector<std::vector<std::uint8_t>> download_frames(std::uint16_t v) {
  ActionGroup g = version(1, v);
  std::vector<rc::Request> r;
  r.push_back(rc::GroupDownloadBegin{1, static_cast<std::uint16_t>(g.actions.size())});
  r.push_back(rc::GroupDownloadServoCount{1, 6});
  r.push_back(
      rc::GroupDownloadBlocks{1, rc::blocks_for_actions(static_cast<int>(g.actions.size()))});
  for (std::size_t i = 0; i < g.actions.size(); ++i) {
    rc::GroupDownloadAction a{
        1, static_cast<std::uint8_t>(i / 255), static_cast<std::uint8_t>(i % 255), v, {}};
    for (const auto& t : g.actions[i].positions) a.targets.push_back({t.servo, t.position});
    r.push_back(a);
  }
  r.push_back(rc::GroupDownloadEnd{1});
  std::vector<std::vector<std::uint8_t>> frames;
  for (const auto& req : r)
    frames.push_back(rc::encode_frame(*rc::encode(req, rc::ServoRange{1, 6})));
  return frames;
}

TEST(CrashSafety, KillDuringDownloadKeepsOldOrNewGroup) {
  TempDir dir;
  std::uint16_t completed = 0;  // newest version whose sub 5 was acknowledged
  for (unsigned trial = 0; trial < 16; ++trial) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {  // child: an emulated xArm receiving downloads of group 1 until killed
      ::close(fds[0]);
      XarmEmulatorOptions options;
      options.state_dir = dir.path();
      Emulated e(options);
      std::uint16_t v = version_of(e.emulator.board().store().find(1), 1).value_or(0) + 1;
      for (;; ++v) {
        for (const auto& frame : download_frames(v)) {
          e.out.clear();
          e.send(frame);
          if (e.out.size() != 1) ::_exit(4);  // every frame acknowledged
          bool end = e.out[0].data[0] == 5;
          write_u32(fds[1], end ? (0x80000000u | v) : 0u);
        }
      }
    }
    ::close(fds[1]);
    // Kill at a frame number spread over a whole download, sometimes during sub 5's write.
    unsigned events = 1 + (trial * 211) % 1500;
    std::uint32_t m = 0;
    for (unsigned i = 0; i < events && read_u32(fds[0], m); ++i)
      if (m & 0x80000000u) completed = static_cast<std::uint16_t>(m);
    spin(trial * 7000);
    kill_and_reap(pid);
    while (read_u32(fds[0], m))
      if (m & 0x80000000u) completed = static_cast<std::uint16_t>(m);
    ::close(fds[0]);

    GroupStore store(dir.path());
    auto v = version_of(store.find(1), 1);
    if (completed == 0) {
      EXPECT_TRUE(store.find(1) == nullptr || v == 1) << "trial " << trial;
      continue;
    }
    ASSERT_TRUE(v.has_value()) << "trial " << trial << ": group 1 corrupt or lost";
    EXPECT_GE(*v, completed) << "trial " << trial;
    EXPECT_LE(*v, completed + 1) << "trial " << trial;
  }
}

}  // namespace
}  // namespace armctl::xarm::test

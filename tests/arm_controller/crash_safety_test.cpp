// kill -9 at varied instants while the arm controller stores action groups that a host
// downloads: every group it acknowledged must be found intact afterwards, old or new, in
// its group memory file (core-memory.bin). The parent synchronises on pipe messages from
// the child (no sleeps): it kills after the child reports k acknowledged downloads, k varied
// per trial, plus a varied spin so the kill also lands mid-download.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>

#include "controller_rig.hpp"
#include "portable_controller/group_store.hpp"
#include "support/killed_child.hpp"

namespace armctl::arm_controller::testing {
namespace {

using robot_commands::GroupAction;
using armctl::testing::kill_after_reports;
using armctl::testing::write_u32;

// Version v of group g: v in every action's time, positions derived from both (joints 2..4,
// whose whole 0..1000 range is allowed).
std::vector<GroupAction> version(std::uint8_t g, std::uint16_t v) {
  std::vector<GroupAction> actions;
  const std::size_t count = 20 + (v * 37u + g) % 80;
  for (std::size_t i = 0; i < count; ++i) {
    GroupAction a{v, {}};
    for (std::uint8_t s = 2; s <= 4; ++s)
      a.targets.push_back({s, static_cast<std::uint16_t>((v + i * s + g) % 1001)});
    actions.push_back(std::move(a));
  }
  return actions;
}

// The version of group g stored in the memory file, if it is exactly one of them.
std::optional<std::uint16_t> stored_version(const std::filesystem::path& file, std::uint8_t g) {
  FileGroupMemory memory(file, CoreDevice::memory_size);
  std::vector<controller::GroupStore::Entry> directory(CoreDevice::group_entries);
  controller::GroupStore store;
  store.begin(&memory, memory.size() - controller::ControllerCore::settings_bytes, directory.data(),
              CoreDevice::group_entries);
  controller::GroupInfo info{};
  if (!store.find(g, &info)) return std::nullopt;
  std::vector<GroupAction> found;
  for (std::uint16_t i = 0; i < info.action_count; ++i) {
    std::uint16_t ms = 0;
    std::uint8_t servos[7];
    std::uint16_t positions[7];
    if (!store.read_action(info, i, &ms, servos, positions)) return std::nullopt;
    GroupAction a{ms, {}};
    for (std::uint8_t k = 0; k < info.servo_count; ++k) a.targets.push_back({servos[k], positions[k]});
    found.push_back(std::move(a));
  }
  if (found.empty() || found != version(g, found[0].time_ms)) return std::nullopt;
  return found[0].time_ms;
}

constexpr std::uint8_t kGroups = 3;

TEST(CrashSafety, KillDuringDownloadsNeverLosesOrCorruptsAnAcknowledgedGroup) {
  TempDir dir;
  std::uint16_t acked[kGroups] = {0, 0, 0};  // newest version each group was acknowledged at
  for (unsigned trial = 0; trial < 16; ++trial) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {  // child: the controller, and a host downloading new versions until killed
      ::close(fds[0]);
      Rig rig(dir.path, 115200);
      std::uint16_t v = 1;
      for (std::uint8_t g = 0; g < kGroups; ++g)
        if (auto have = stored_version(dir.path / CoreDevice::memory_file, g)) v = std::max<std::uint16_t>(v, *have + 1);
      for (;; ++v)
        for (std::uint8_t g = 0; g < kGroups; ++g) {
          if (!rig.client->download_group(g, version(g, v)).ok()) ::_exit(3);
          write_u32(fds[1], std::uint32_t{g} << 16 | v);
        }
    }
    ::close(fds[1]);
    ASSERT_TRUE(kill_after_reports(fds[0], pid, 1 + (trial * 5) % 7, trial * 30000, acked))
        << "trial " << trial << ": the child ended";

    for (std::uint8_t g = 0; g < kGroups; ++g) {
      if (acked[g] == 0) continue;  // never acknowledged: absent or the first version, both fine
      const auto v = stored_version(dir.path / CoreDevice::memory_file, g);
      ASSERT_TRUE(v.has_value()) << "trial " << trial << " group " << int(g) << " corrupt or lost";
      EXPECT_GE(*v, acked[g]) << "trial " << trial << " group " << int(g) << " went back";
      EXPECT_LE(*v, acked[g] + 1) << "trial " << trial;
    }
  }
  std::printf("acknowledged versions at the end: %u %u %u\n", acked[0], acked[1], acked[2]);
}

}  // namespace
}  // namespace armctl::arm_controller::testing

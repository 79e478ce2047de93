// Group storage: persistence across emulator restarts, validation on load, quarantine of
// corrupt files, stray temporary files.
#include "harness.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <memory>

#include "core/atomic_file.hpp"
#include "devices/rc_board/group_file_format.hpp"
#include "devices/rc_board/group_store.hpp"

namespace armctl::xarm::test {
namespace {

using rc_board::ActionGroup;
using rc_board::GroupStore;

ActionGroup sample(std::uint16_t tag, std::size_t count = 5) {
  ActionGroup g{2, {}};
  for (std::size_t i = 0; i < count; ++i)
    g.actions.push_back(
        {tag, {{1, static_cast<std::uint16_t>(i % 1001)}, {2, std::nullopt}}});  // servo 2 left alone
  return g;
}

TEST(GroupStore, GroupsSurviveEmulatorRestart) {
  TempDir dir;
  XarmEmulatorOptions options;
  options.state_dir = dir.path();
  {
    Emulated e(options);
    e.send(vector_bytes("GroupDownload begin group 4, 300 actions"));
    e.send(vector_bytes("GroupDownload servos per action = 3"));
    e.send(vector_bytes("GroupDownload blocks 0 and 1 (<= 510 actions)"));
    for (int i = 0; i < 300; ++i)
      e.send(rc::GroupDownloadAction{4,
                                     static_cast<std::uint8_t>(i / 255),
                                     static_cast<std::uint8_t>(i % 255),
                                     20,
                                     {{1, 100}, {2, static_cast<std::uint16_t>(i)}, {3, 900}}});
    e.send(vector_bytes("GroupDownload end group 4"));
    ASSERT_EQ(e.stats().ignored(), 0u);
  }
  Emulated restarted(options);  // new instance, same state dir
  const auto* g = restarted.emulator.board().store().find(4);
  ASSERT_NE(g, nullptr);
  ASSERT_EQ(g->actions.size(), 300u);
  EXPECT_EQ(g->actions[299].positions[1].position, 299);
  restarted.send(rc::GroupRun{4, 1});
  restarted.advance_ms(300 * 20 + 1000);   // the first move is slower (speed limit)
  EXPECT_EQ(restarted.out.back().cmd, 8);  // played to the end
  EXPECT_EQ(restarted.position(2), 299);
  restarted.send(rc::GroupErase{4});
  Emulated after_erase(options);
  EXPECT_EQ(after_erase.emulator.board().store().find(4), nullptr);
}

TEST(GroupStore, FileFormatRoundTripsAndRejectsEveryCorruption) {
  auto bytes = rc_board::encode_group_file(3, sample(77));
  auto back = rc_board::decode_group_file(bytes, 3);
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(*back, sample(77));
  EXPECT_FALSE(rc_board::decode_group_file(bytes, 4).ok());  // named for another group
  for (std::size_t cut = 0; cut < bytes.size(); ++cut)       // every torn length
    EXPECT_FALSE(rc_board::decode_group_file(std::span(bytes).first(cut), 3).ok()) << cut;
  for (std::size_t i = 0; i < bytes.size(); ++i) {  // every single-byte corruption
    auto bad = bytes;
    bad[i] ^= 0x5A;
    EXPECT_FALSE(rc_board::decode_group_file(bad, 3).ok()) << i;
  }
}

TEST(GroupStore, CorruptFilesAreQuarantinedAndTemporaryFilesRemoved) {
  TempDir dir;
  {
    GroupStore store(dir.path());
    ASSERT_TRUE(store.save(1, sample(1)).ok());
    ASSERT_TRUE(store.save(2, sample(2)).ok());
  }
  {
    std::fstream f(dir.path() / "group-002.grp", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(20);
    f.put('\x7F');
  }
  std::ofstream(dir.path() / "group-001.grp.tmp-12345") << "half a group";
  GroupStore store(dir.path());
  ASSERT_NE(store.find(1), nullptr);
  EXPECT_EQ(*store.find(1), sample(1));
  EXPECT_EQ(store.find(2), nullptr);
  ASSERT_EQ(store.problems().size(), 2u);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "group-001.grp.tmp-12345"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "group-002.grp"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "quarantine"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path() / "quarantine"),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(GroupStore, UnusableStateDirIsAClearError) {
  TempDir dir;
  std::ofstream(dir.path() / "file") << "x";
  try {
    GroupStore store(dir.path() / "file" / "sub");
    FAIL() << "expected an error";
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::io);
    EXPECT_NE(std::string(e.what()).find("state directory"), std::string::npos) << e.what();
  }
}

TEST(GroupStore, FailedSaveLeavesGroupUnchanged) {
  TempDir dir;
  GroupStore store(dir.path());
  ASSERT_TRUE(store.save(5, sample(1)).ok());
  // Make the rename fail (works as root too): a non-empty directory where the file goes.
  std::filesystem::remove(dir.path() / "group-005.grp");
  std::filesystem::create_directories(dir.path() / "group-005.grp" / "x");
  auto status = store.save(5, sample(9));
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.error().kind, ErrorKind::io);
  EXPECT_NE(status.error().message.find("group-005.grp"), std::string::npos);
  EXPECT_EQ(*store.find(5), sample(1));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_FALSE(is_temporary_name(entry.path().filename().string()));
}

// A temporary file that cannot be removed (a read-only state dir; as root a non-empty
// directory of that name stands in) is reported, and the store starts with its groups.
TEST(GroupStore, AnUnremovableLeftoverTemporaryFileDoesNotStopTheStart) {
  TempDir dir;
  {
    GroupStore store(dir.path());
    ASSERT_TRUE(store.save(1, sample(1)).ok());
  }
  std::filesystem::create_directories(dir.path() / "group-001.grp.tmp-4242" / "x");
  std::unique_ptr<GroupStore> store;
  ASSERT_NO_THROW(store = std::make_unique<GroupStore>(dir.path()));
  ASSERT_NE(store->find(1), nullptr);
  ASSERT_EQ(store->problems().size(), 1u);
  EXPECT_NE(store->problems()[0].find("could not remove unfinished save group-001.grp.tmp-4242"), std::string::npos)
      << store->problems()[0];
}

// Odd entries among the state files are reported and skipped, none read unbounded: a
// directory, a FIFO (reading it would block), a sparse 2 GB file, names outside 0..254.
TEST(GroupStore, OddEntriesAreReportedAndSkippedUnread) {
  TempDir dir;
  {
    GroupStore store(dir.path());
    ASSERT_TRUE(store.save(7, sample(7)).ok());
  }
  std::filesystem::create_directories(dir.path() / "group-002.grp");
  ASSERT_EQ(::mkfifo((dir.path() / "group-003.grp").c_str(), 0600), 0);
  {
    const int fd = ::open((dir.path() / "group-004.grp").c_str(), O_WRONLY | O_CREAT, 0600);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::ftruncate(fd, off_t{2} << 30), 0);  // holes only: no disk used
    ::close(fd);
  }
  std::ofstream(dir.path() / "group-999.grp") << "x";
  std::ofstream(dir.path() / "group-abc.grp") << "x";

  const auto started = std::chrono::steady_clock::now();
  GroupStore store(dir.path());
  const auto took = std::chrono::steady_clock::now() - started;
  EXPECT_LT(took, std::chrono::seconds(2)) << "a 2 GB file was read";  // 10 s before
  ASSERT_NE(store.find(7), nullptr);
  EXPECT_EQ(store.size(), 1u);
  auto reported = [&](const std::string& part) {
    for (const auto& p : store.problems())
      if (p.find(part) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(reported("group-002.grp is not a regular file (a directory)"));
  EXPECT_TRUE(reported("group-003.grp is not a regular file (a FIFO)"));
  EXPECT_TRUE(reported("group-004.grp is 2147483648 bytes"));
  EXPECT_TRUE(reported("group-999.grp: not a group file name"));
  EXPECT_TRUE(reported("group-abc.grp: not a group file name"));
  EXPECT_EQ(store.problems().size(), 5u);
  // Nothing was moved or deleted: the entries are the user's to look at.
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "group-004.grp"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "quarantine"));
}

TEST(Atomic, ReadWholeFileChecksTypeAndSizeFirst) {
  TempDir dir;
  std::ofstream(dir.path() / "small") << "12345";
  auto small = read_whole_file(dir.path() / "small", 5);
  ASSERT_TRUE(small.ok()) << small.error().message;
  EXPECT_EQ((*small)->size(), 5u);
  auto large = read_whole_file(dir.path() / "small", 4);
  ASSERT_FALSE(large.ok());
  EXPECT_NE(large.error().message.find("is 5 bytes"), std::string::npos) << large.error().message;
  auto missing = read_whole_file(dir.path() / "none", 4);
  ASSERT_TRUE(missing.ok());
  EXPECT_FALSE(missing->has_value());
  EXPECT_FALSE(read_whole_file(dir.path(), 4).ok());
}

TEST(Atomic, TemporaryNamesAreRecognised) {
  EXPECT_TRUE(is_temporary_name("group-001.grp.tmp-77"));
  EXPECT_FALSE(is_temporary_name("group-001.grp"));
}

}  // namespace
}  // namespace armctl::xarm::test

// write_file_atomically() and check_writable(): a symlink is written through (the target
// replaced, the link kept), the replaced file's mode kept, a read-only file refused and left
// as it is, a missing directory named before anything is written.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/atomic_file.hpp"

namespace armctl {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "armctl-atomic-file-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  static Status write(const fs::path& path, const std::string& text) {
    return write_file_atomically(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  }
  static std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static unsigned mode(const fs::path& path) {
    struct stat st {};
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return st.st_mode & 07777;
  }
  void make(const fs::path& path, const std::string& text, unsigned mode) {
    std::ofstream(path, std::ios::binary) << text;
    ASSERT_EQ(::chmod(path.c_str(), mode), 0);
  }
  fs::path dir_;
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_F(AtomicFile, KeepsTheModeOfTheFileItReplaces) {
  make(dir_ / "a.points", "old\n", 0600);
  ASSERT_TRUE(write(dir_ / "a.points", "new\n"));
  EXPECT_EQ(slurp(dir_ / "a.points"), "new\n");
  EXPECT_EQ(mode(dir_ / "a.points"), 0600u);  // was 0644: the new file's own mode
}

TEST_F(AtomicFile, RefusesAReadOnlyFileAndLeavesIt) {
  make(dir_ / "a.points", "old\n", 0444);
  auto s = write(dir_ / "a.points", "new\n");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::io);
  EXPECT_EQ(s.error().message, "cannot write " + (dir_ / "a.points").string() +
                                   ": it is read-only (mode 0444); make it writable (chmod u+w) to replace it, "
                                   "or write another file");
  EXPECT_EQ(slurp(dir_ / "a.points"), "old\n");
  EXPECT_EQ(mode(dir_ / "a.points"), 0444u);
  EXPECT_FALSE(check_writable(dir_ / "a.points"));
}

TEST_F(AtomicFile, WritesThroughASymlinkToItsTarget) {
  fs::create_directory(dir_ / "real");
  make(dir_ / "real" / "cell.points", "old\n", 0640);
  fs::create_symlink("real/cell.points", dir_ / "cell.points");  // relative, read from the link's directory
  ASSERT_TRUE(write(dir_ / "cell.points", "new\n"));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "cell.points")));
  EXPECT_EQ(fs::read_symlink(dir_ / "cell.points"), "real/cell.points");
  EXPECT_EQ(slurp(dir_ / "real" / "cell.points"), "new\n");
  EXPECT_EQ(mode(dir_ / "real" / "cell.points"), 0640u);
  EXPECT_EQ(fs::directory_iterator(dir_ / "real")->path().filename(), "cell.points");  // no stray temporary
}

TEST_F(AtomicFile, ADanglingLinkCreatesItsTargetAndStaysALink) {
  fs::create_symlink(dir_ / "target.rec", dir_ / "link.rec");
  ASSERT_TRUE(check_writable(dir_ / "link.rec"));
  ASSERT_TRUE(write(dir_ / "link.rec", "new\n"));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "link.rec")));
  EXPECT_EQ(slurp(dir_ / "target.rec"), "new\n");
}

TEST_F(AtomicFile, AReadOnlyTargetOfALinkIsRefusedNamingBoth) {
  make(dir_ / "target.points", "old\n", 0444);
  fs::create_symlink(dir_ / "target.points", dir_ / "link.points");
  auto s = write(dir_ / "link.points", "new\n");
  ASSERT_FALSE(s);
  EXPECT_TRUE(contains(s.error().message, "cannot write " + (dir_ / "link.points").string() + " (a link to " +
                                              (dir_ / "target.points").string() + "): it is read-only (mode 0444)"))
      << s.error().message;
  EXPECT_EQ(slurp(dir_ / "target.points"), "old\n");
}

TEST_F(AtomicFile, ALinkLoopIsRefused) {
  fs::create_symlink(dir_ / "b", dir_ / "a");
  fs::create_symlink(dir_ / "a", dir_ / "b");
  auto s = check_writable(dir_ / "a");
  ASSERT_FALSE(s);
  EXPECT_TRUE(contains(s.error().message, "more than 40 symbolic links in a row")) << s.error().message;
}

TEST_F(AtomicFile, CheckWritableNamesAMissingDirectoryOrAFileOfAnotherKind) {
  EXPECT_TRUE(check_writable(dir_ / "new.rec"));
  auto missing = check_writable(dir_ / "nodir" / "x.rec");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message, "cannot write " + (dir_ / "nodir" / "x.rec").string() + ": directory " +
                                         (dir_ / "nodir").string() + " does not exist");
  EXPECT_FALSE(write(dir_ / "nodir" / "x.rec", "x"));
  EXPECT_FALSE(fs::exists(dir_ / "nodir"));
  make(dir_ / "file", "", 0644);
  auto under_file = check_writable(dir_ / "file" / "x.rec");
  ASSERT_FALSE(under_file);
  EXPECT_TRUE(contains(under_file.error().message, (dir_ / "file").string() + " is not a directory (a regular file)"))
      << under_file.error().message;
  auto a_dir = check_writable(dir_);
  ASSERT_FALSE(a_dir);
  EXPECT_TRUE(contains(a_dir.error().message, "it is not a regular file (a directory)")) << a_dir.error().message;
}

}  // namespace
}  // namespace armctl

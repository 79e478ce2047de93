// read_regular_file(): a directory, a FIFO or an oversized (even sparse) file is refused at
// once with the path named; a regular file within the limit is read whole. read_text_file():
// the same without a leading UTF-8 byte-order mark.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/regular_file.hpp"

namespace armctl {
namespace {

namespace fs = std::filesystem;

class RegularFile : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "armctl-regular-file-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_F(RegularFile, ReadsARegularFileWhole) {
  std::ofstream(dir_ / "a.txt") << "servos 1\n100 1=500\n";
  auto text = read_regular_file(dir_ / "a.txt", "group file", 1024);
  ASSERT_TRUE(text) << text.error().message;
  EXPECT_EQ(*text, "servos 1\n100 1=500\n");
}

TEST_F(RegularFile, ADirectoryIsNotARegularFile) {
  auto text = read_regular_file(dir_, "group file", 1024);
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().kind, ErrorKind::io);
  EXPECT_TRUE(contains(text.error().message, "group file " + dir_.string() + " is not a regular file (a directory)"))
      << text.error().message;
}

TEST_F(RegularFile, AFifoWithNoWriterIsRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto text = read_regular_file(fifo, "group file", 1024);  // blocked for ever before
  ASSERT_FALSE(text);
  EXPECT_TRUE(contains(text.error().message, fifo.string() + " is not a regular file (a FIFO)")) << text.error().message;
}

TEST_F(RegularFile, ASparseHugeFileIsRefusedBeforeItIsRead) {
  const fs::path big = dir_ / "big.grp";
  {
    const int fd = ::open(big.c_str(), O_WRONLY | O_CREAT, 0600);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::ftruncate(fd, off_t{2} << 30), 0);  // 2 GB of holes: costs no disk
    ::close(fd);
  }
  auto text = read_regular_file(big, "group file", 1 << 20);
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().kind, ErrorKind::invalid_config);
  EXPECT_TRUE(contains(text.error().message, "is 2147483648 bytes, larger than allowed (1048576 bytes)"))
      << text.error().message;
}

TEST_F(RegularFile, AMissingFileAndControlCharactersInItsNameAreReported) {
  auto text = read_regular_file(dir_ / "\x1b]0;x\x07.grp", "group file", 1024);
  ASSERT_FALSE(text);
  EXPECT_TRUE(contains(text.error().message, "\\x1b]0;x\\x07.grp: no such file")) << text.error().message;
  EXPECT_FALSE(contains(text.error().message, "\x1b"));
}

TEST_F(RegularFile, ATextFileIsReadWithoutItsByteOrderMark) {
  std::ofstream(dir_ / "a.prog", std::ios::binary) << "\xEF\xBB\xBFptp home\n";
  auto text = read_text_file(dir_ / "a.prog", "program", 1024);
  ASSERT_TRUE(text) << text.error().message;
  EXPECT_EQ(*text, "ptp home\n");
  // Only a mark at the start, only once; the raw reader keeps every byte (binary files).
  std::ofstream(dir_ / "b.prog", std::ios::binary) << "\xEF\xBB\xBF\xEF\xBB\xBFx \xEF\xBB\xBF";
  EXPECT_EQ(*read_text_file(dir_ / "b.prog", "program", 1024), "\xEF\xBB\xBFx \xEF\xBB\xBF");
  EXPECT_EQ(*read_regular_file(dir_ / "a.prog", "program", 1024), "\xEF\xBB\xBFptp home\n");
  std::ofstream(dir_ / "c.prog", std::ios::binary) << "\xEF\xBB";
  EXPECT_EQ(*read_text_file(dir_ / "c.prog", "program", 1024), "\xEF\xBB");
}

}  // namespace
}  // namespace armctl

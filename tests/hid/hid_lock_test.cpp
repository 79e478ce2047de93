// Exclusive use of a hidraw node (transport/hid_device_lock.hpp) on temp files: a second
// armctl is refused and told who holds the node; programs that merely have it open are
// named. "Other programs" are forked children that hold the file until told to exit.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "transport/hid_device_lock.hpp"

namespace armctl::transport {
namespace {

namespace fs = std::filesystem;

fs::path temp_node() {
  const fs::path dir = fs::temp_directory_path() / ("armctl-hid-lock-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path node = dir / "hidraw7";
  std::ofstream(node).put('\0');
  return node;
}

// A child that opens `path` (and flocks it if asked), reports ready, and waits to be told to go.
class Holder {
 public:
  Holder(const fs::path& path, bool lock) {
    int ready[2], go[2];
    if (::pipe(ready) != 0 || ::pipe(go) != 0) std::abort();
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(ready[0]);
      ::close(go[1]);  // else the child would wait for its own end of the pipe
      const int fd = ::open(path.c_str(), O_RDONLY);
      if (fd < 0 || (lock && ::flock(fd, LOCK_EX) != 0)) ::_exit(2);
      char c = 'r';
      if (::write(ready[1], &c, 1) != 1) ::_exit(3);
      if (::read(go[0], &c, 1) < 0) ::_exit(4);
      ::_exit(0);
    }
    ::close(ready[1]);
    ::close(go[0]);
    go_ = go[1];
    char c = 0;
    if (::read(ready[0], &c, 1) != 1) std::abort();
    ::close(ready[0]);
  }
  ~Holder() {
    ::close(go_);
    ::waitpid(pid_, nullptr, 0);
  }
  int pid() const { return pid_; }

 private:
  int pid_ = -1;
  int go_ = -1;
};

TEST(NodeHolders, ProgramsWithTheNodeOpenAreNamedButNotThisOne) {
  const fs::path node = temp_node();
  const int self_fd = ::open(node.c_str(), O_RDONLY);
  ASSERT_GE(self_fd, 0);
  EXPECT_TRUE(programs_holding(node).empty());  // this process does not count
  {
    Holder other(node, false);
    const auto holders = programs_holding(node);
    ASSERT_EQ(holders.size(), 1u);
    EXPECT_EQ(holders[0].pid, other.pid());
    EXPECT_FALSE(holders[0].program.empty());
    EXPECT_EQ(holders_text(holders),
              holders[0].program + " (pid " + std::to_string(other.pid()) + ")");
  }
  EXPECT_TRUE(programs_holding(node).empty());
  ::close(self_fd);
}

TEST(NodeHolders, MatchedThroughSymlinks) {
  const fs::path node = temp_node();
  const fs::path link = node.parent_path() / "xarm";
  fs::remove(link);
  fs::create_symlink(node, link);
  Holder other(node, false);
  const auto holders = programs_holding(link);
  ASSERT_EQ(holders.size(), 1u);
  EXPECT_EQ(holders[0].pid, other.pid());
}

TEST(NodeLockTest, SecondLockIsRefusedNamingTheHolder) {
  const fs::path node = temp_node();
  Holder other(node, true);
  try {
    NodeLock lock(node);
    FAIL() << "locked a node another process holds";
  } catch (const ArmctlError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.error().kind, ErrorKind::io);
    EXPECT_NE(m.find("another program is using the board"), std::string::npos) << m;
    EXPECT_NE(m.find("(pid " + std::to_string(other.pid()) + ")"), std::string::npos) << m;
  }
}

TEST(NodeLockTest, LockIsExclusiveAndReleased) {
  const fs::path node = temp_node();
  {
    NodeLock first(node);
    EXPECT_THROW(NodeLock second(node), ArmctlError);  // a new open: its own flock fails
  }
  EXPECT_NO_THROW(NodeLock again(node));
}

TEST(NodeLockTest, MissingNodeNamesThePath) {
  try {
    NodeLock lock("/nonexistent/hidraw99");
    FAIL();
  } catch (const ArmctlError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/hidraw99"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos);
  }
}

}  // namespace
}  // namespace armctl::transport

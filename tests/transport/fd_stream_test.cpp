// FdStream::write never waits without a deadline: a peer that stops reading (a pipe or pty
// nobody reads) makes it throw a timeout saying how much got through, while a peer that
// reads slowly but keeps reading gets every byte.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "transport/fd_stream.hpp"
#include "transport/pty.hpp"

namespace armctl::transport {
namespace {

using namespace std::chrono_literals;

// More than any pipe or pty buffer holds.
const std::vector<std::uint8_t> kMegabyte(1 << 20, 0x55);

void expect_write_times_out(FdStream& stream, Duration timeout) {
  stream.set_write_timeout(timeout);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    stream.write(kMegabyte);
    ADD_FAILURE() << "a megabyte went into a peer that reads nothing";
  } catch (const ArmctlError& e) {
    const auto took = std::chrono::steady_clock::now() - t0;
    EXPECT_EQ(e.error().kind, ErrorKind::timeout) << e.what();
    EXPECT_NE(std::string(e.what()).find("of 1048576 bytes and then none within 100 ms"),
              std::string::npos)
        << e.what();
    EXPECT_GE(took, timeout);
    EXPECT_LT(took, timeout + 5s) << "the deadline bounds the wait";
  }
}

TEST(FdStreamWrite, APipeNobodyReadsTimesOut) {
  int fds[2];
  ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);  // blocking: FdStream must make it non-blocking
  FdStream writer(fds[1], "test pipe");
  expect_write_times_out(writer, 100ms);
  ::close(fds[0]);
}

TEST(FdStreamWrite, APtyWhoseSlaveNobodyReadsTimesOut) {
  Pty pty = Pty::open();
  expect_write_times_out(pty.master(), 100ms);
}

TEST(FdStreamWrite, ASlowReaderThatKeepsReadingGetsEveryByte) {
  int fds[2];
  ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
  std::size_t received = 0;
  std::thread reader([&] {
    std::vector<std::uint8_t> buf(512);  // small reads: the writer waits for room often
    for (;;) {
      const ssize_t n = ::read(fds[0], buf.data(), buf.size());
      if (n <= 0) break;
      received += static_cast<std::size_t>(n);
    }
  });
  {
    FdStream writer(fds[1], "test pipe");
    writer.set_write_timeout(10s);
    EXPECT_NO_THROW(writer.write(kMegabyte));
  }  // closes the write end: the reader sees the end of the data
  reader.join();
  EXPECT_EQ(received, kMegabyte.size());
  ::close(fds[0]);
}

}  // namespace
}  // namespace armctl::transport

// For tests that kill -9 a child process mid-work (crash safety): the child reports
// progress as 32-bit words on a pipe, the parent waits for k reports, spins a varied while
// and kills. Synchronised on the pipe, never on sleeps.
#pragma once

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>

namespace armctl::testing {

inline void write_u32(int fd, std::uint32_t value) { [[maybe_unused]] ssize_t n = ::write(fd, &value, sizeof value); }

// False at end of file (the child is gone and every report read).
inline bool read_u32(int fd, std::uint32_t& value) {
  std::size_t got = 0;
  auto* p = reinterpret_cast<char*>(&value);
  while (got < sizeof value) {
    const ssize_t n = ::read(fd, p + got, sizeof value - got);
    if (n <= 0) return false;
    got += static_cast<std::size_t>(n);
  }
  return true;
}

// Busy work of a varied length, so a kill also lands between two reports.
inline void spin(unsigned iterations) {
  volatile unsigned sink = 0;
  for (unsigned i = 0; i < iterations; ++i) sink = sink + i;
}

inline void kill_and_reap(pid_t pid) {
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child ended by itself, status " << status;
}

// The parent's side of one trial: waits for `reports` reports (each `group << 16 | version`,
// the newest kept in acked[group]), spins `spin_iterations`, kills the child, takes the
// reports it wrote before it died, and closes `fd`. False if the child ended before
// `reports` reports.
inline bool kill_after_reports(int fd, pid_t pid, unsigned reports, unsigned spin_iterations,
                               std::uint16_t* acked) {
  bool all = true;
  std::uint32_t m = 0;
  for (unsigned i = 0; i < reports && all; ++i) {
    all = read_u32(fd, m);
    if (all) acked[m >> 16] = static_cast<std::uint16_t>(m & 0xFFFF);
  }
  if (all) spin(spin_iterations);
  kill_and_reap(pid);
  while (read_u32(fd, m)) acked[m >> 16] = static_cast<std::uint16_t>(m & 0xFFFF);
  ::close(fd);
  return all;
}

}  // namespace armctl::testing

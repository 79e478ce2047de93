// Runs the real armctl binary (ARMCTL_BINARY_DIR/armctl) through the shell and collects its
// output and exit status, for end-to-end CLI tests.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace armctl::cli_test {

struct CliRun {
  int status;       // exit status; -1 if killed by a signal
  std::string out;  // stdout (and stderr, unless separated)
};

// `args` is shell text; `redirect` decides what happens to stderr ("2>&1": mixed in).
inline CliRun run_armctl(const std::string& args, const std::string& redirect = "2>&1") {
  const std::string cmd = std::string(ARMCTL_BINARY_DIR) + "/armctl " + args + " " + redirect;
  FILE* p = ::popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf{};
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int st = ::pclose(p);
  return CliRun{WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

}  // namespace armctl::cli_test

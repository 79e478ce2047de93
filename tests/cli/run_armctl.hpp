// Runs the real armctl binary (ARMCTL_BINARY_DIR/armctl) through the shell and collects its
// output and exit status, for end-to-end CLI tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

#include <array>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

// Appends what one read() of `fd` gives to `into`; false at end of file or on an error.
inline bool read_some(int fd, std::string& into) {
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      into.append(buf, static_cast<std::size_t>(n));
      return true;
    }
    if (n < 0 && errno == EINTR) continue;
    return false;
  }
}

// Shell-free argument lists: "move 1=500 --wait" -> {"move", "1=500", "--wait"}.
inline std::vector<std::string> split_args(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> args;
  for (std::string a; in >> a;) args.push_back(a);
  return args;
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Every non-empty line of `out` must be one JSON document (throws if not).
inline std::vector<nlohmann::json> json_lines(const std::string& out) {
  std::vector<nlohmann::json> docs;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) docs.push_back(nlohmann::json::parse(line));
  }
  return docs;
}

}  // namespace armctl::cli_test

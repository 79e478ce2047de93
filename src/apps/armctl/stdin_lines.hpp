// Standard input a line at a time for interactive commands (teach), from a terminal or a
// script, that also notices Ctrl-C: waits in poll() so that a signal flag is seen within
// 100 ms whatever the handler's SA_RESTART.
#pragma once

#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <optional>
#include <string>

namespace armctl::cli {

class StdinLines {
 public:
  explicit StdinLines(const std::atomic<bool>& interrupted) : interrupted_(interrupted) {}

  // The next line (without its newline); nullopt at the end of input or on Ctrl-C. A last
  // line without a newline counts.
  std::optional<std::string> next() {
    for (;;) {
      if (auto line = take_line()) return line;
      if (interrupted_ || eof_) {
        if (eof_ && !buffer_.empty() && !interrupted_) {
          std::string last;
          last.swap(buffer_);
          return last;
        }
        return std::nullopt;
      }
      fill(100);
    }
  }

  // Without waiting: whether a line (Enter) has come; then whether the input has ended.
  bool line_ready() {
    fill(0);
    return buffer_.find('\n') != std::string::npos;
  }
  bool ended() const { return eof_; }

 private:
  std::optional<std::string> take_line() {
    const auto nl = buffer_.find('\n');
    if (nl == std::string::npos) return std::nullopt;
    std::string line = buffer_.substr(0, nl);
    buffer_.erase(0, nl + 1);
    return line;
  }
  void fill(int timeout_ms) {
    if (eof_) return;
    pollfd p{STDIN_FILENO, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) <= 0) return;
    char buf[4096];
    const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
    if (n > 0)
      buffer_.append(buf, static_cast<std::size_t>(n));
    else if (n == 0 || (p.revents & (POLLHUP | POLLERR | POLLNVAL)))
      eof_ = true;
  }

  const std::atomic<bool>& interrupted_;
  std::string buffer_;
  bool eof_ = false;
};

}  // namespace armctl::cli

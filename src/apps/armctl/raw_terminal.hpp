// Standard input as `armctl jog` reads it: when it is a terminal, in raw mode (each key at
// once, no echo, Ctrl-C as a key) until destroyed, also on errors; keys read without
// waiting. When it is a pipe or a file, the same reads, and its end is reported.
#pragma once

#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <string>

namespace armctl::cli {

class RawTerminal {
 public:
  explicit RawTerminal(int fd = STDIN_FILENO) : fd_(fd) {
    if (!isatty(fd_) || tcgetattr(fd_, &saved_) != 0) return;
    termios raw = saved_;
    // Keys one by one, not echoed, Ctrl-C delivered as a byte; output processing stays on.
    raw.c_lflag &= ~tcflag_t(ICANON | ECHO | ISIG | IEXTEN);
    raw.c_iflag &= ~tcflag_t(IXON | ICRNL);
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    raw_ = tcsetattr(fd_, TCSANOW, &raw) == 0;
  }
  ~RawTerminal() {
    if (raw_) tcsetattr(fd_, TCSANOW, &saved_);
  }
  RawTerminal(const RawTerminal&) = delete;
  RawTerminal& operator=(const RawTerminal&) = delete;

  bool is_terminal() const { return raw_; }
  // Whatever has arrived, without waiting ("" if nothing).
  std::string read_available() {
    std::string bytes;
    pollfd p{fd_, POLLIN, 0};
    while (!ended_ && poll(&p, 1, 0) > 0 && (p.revents & (POLLIN | POLLHUP))) {
      char buffer[256];
      const ssize_t n = read(fd_, buffer, sizeof buffer);
      if (n <= 0) {
        ended_ = !raw_;  // a terminal with nothing to read is not at its end
        break;
      }
      bytes.append(buffer, std::size_t(n));
    }
    return bytes;
  }
  // A pipe or file ended.
  bool ended() const { return ended_; }

 private:
  int fd_;
  termios saved_{};
  bool raw_ = false;
  bool ended_ = false;
};

}  // namespace armctl::cli

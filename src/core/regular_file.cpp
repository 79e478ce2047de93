#include "core/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/core.h>

#include "core/printable.hpp"

namespace armctl {
const char* file_type_name(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "not a file";
}

namespace {

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

Result<std::string> read_regular_file(const std::filesystem::path& path, std::string_view what,
                                      std::uintmax_t max_bytes) {
  const std::string name = printable(path.string());
  // O_NONBLOCK: opening a FIFO with no writer must not wait for one. The type is checked on
  // the opened descriptor, so the file cannot be swapped between the check and the read.
  const Fd file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (file.fd < 0) {
    const int err = errno;
    if (err == ENOENT) return Error{ErrorKind::io, fmt::format("cannot open {} {}: no such file", what, name)};
    return Error{ErrorKind::io, fmt::format("cannot open {} {}: {}", what, name, std::strerror(err))};
  }
  struct stat st {};
  if (::fstat(file.fd, &st) != 0)
    return Error{ErrorKind::io, fmt::format("cannot read {} {}: {}", what, name, std::strerror(errno))};
  if (!S_ISREG(st.st_mode))
    return Error{ErrorKind::io,
                 fmt::format("{} {} is not a regular file ({})", what, name, file_type_name(st.st_mode))};
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    return Error{ErrorKind::invalid_config,
                 fmt::format("{} {} is {} bytes, larger than allowed ({} bytes)", what, name, st.st_size, max_bytes)};
  std::string text;
  text.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[16384];
  for (;;) {
    const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      return Error{ErrorKind::io, fmt::format("cannot read {} {}: {}", what, name, std::strerror(errno))};
    if (n == 0) break;
    // The file may grow while it is read: the limit holds for what is read, not only the stat.
    if (text.size() + static_cast<std::size_t>(n) > max_bytes)
      return Error{ErrorKind::invalid_config,
                   fmt::format("{} {} is larger than allowed ({} bytes)", what, name, max_bytes)};
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

Result<std::string> read_text_file(const std::filesystem::path& path, std::string_view what,
                                   std::uintmax_t max_bytes) {
  auto text = read_regular_file(path, what, max_bytes);
  if (text && std::string_view(*text).starts_with(kUtf8Bom)) text->erase(0, kUtf8Bom.size());
  return text;
}

}  // namespace armctl

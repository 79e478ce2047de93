#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/core.h>

#include "core/printable.hpp"

namespace armctl {
namespace {

Error io_error(std::string_view what, const std::filesystem::path& path, int err) {
  return Error{ErrorKind::io, fmt::format("{} {}: {}", what, printable(path.string()), std::strerror(err))};
}

// Closes a file descriptor on every path out of a function.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  int release() {
    int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_;
};

Status fsync_directory(const std::filesystem::path& dir) {
  Fd fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (fd.get() < 0) return io_error("cannot open directory", dir, errno);
  if (::fsync(fd.get()) != 0) return io_error("cannot fsync directory", dir, errno);
  return Ok{};
}

std::filesystem::path parent_of(const std::filesystem::path& path) {
  auto parent = path.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

}  // namespace

Status write_file_atomically(const std::filesystem::path& path,
                             std::span<const std::uint8_t> bytes) {
  auto temp = path;
  temp += fmt::format(".tmp-{}", ::getpid());
  Fd fd(::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) return io_error("cannot create", temp, errno);
  std::size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = ::write(fd.get(), bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      int err = errno;
      ::unlink(temp.c_str());
      return io_error("cannot write", temp, err);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd.get()) != 0) {
    int err = errno;
    ::unlink(temp.c_str());
    return io_error("cannot fsync", temp, err);
  }
  if (::close(fd.release()) != 0) {
    int err = errno;
    ::unlink(temp.c_str());
    return io_error("cannot close", temp, err);
  }
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    int err = errno;
    ::unlink(temp.c_str());
    return io_error("cannot rename into place", path, err);
  }
  return fsync_directory(parent_of(path));
}

Status remove_file_durably(const std::filesystem::path& path) {
  if (::unlink(path.c_str()) != 0) {
    if (errno == ENOENT) return Ok{};
    return io_error("cannot remove", path, errno);
  }
  return fsync_directory(parent_of(path));
}

Result<std::optional<std::vector<std::uint8_t>>> read_whole_file(const std::filesystem::path& path,
                                                                 std::uintmax_t max_bytes) {
  Fd fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) {
    if (errno == ENOENT) return std::optional<std::vector<std::uint8_t>>{};
    return io_error("cannot open", path, errno);
  }
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) return io_error("cannot stat", path, errno);
  if (!S_ISREG(st.st_mode))
    return Error{ErrorKind::io, fmt::format("{} is not a regular file ({})", printable(path.string()),
                                            S_ISDIR(st.st_mode) ? "a directory" : S_ISFIFO(st.st_mode) ? "a FIFO" : "a special file")};
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    return Error{ErrorKind::io, fmt::format("{} is {} bytes, more than such a file can hold ({}): not read",
                                            printable(path.string()), st.st_size, max_bytes)};
  std::vector<std::uint8_t> bytes;
  bytes.reserve(static_cast<std::size_t>(st.st_size));
  std::uint8_t buffer[4096];
  for (;;) {
    ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return io_error("cannot read", path, errno);
    if (n == 0) break;
    if (bytes.size() + static_cast<std::size_t>(n) > max_bytes)  // grew while being read
      return Error{ErrorKind::io, fmt::format("{} grew beyond {} bytes while being read: not read",
                                              printable(path.string()), max_bytes)};
    bytes.insert(bytes.end(), buffer, buffer + n);
  }
  return std::optional<std::vector<std::uint8_t>>{std::move(bytes)};
}

bool is_temporary_name(std::string_view file_name) {
  return file_name.find(".tmp-") != std::string_view::npos;
}

}  // namespace armctl

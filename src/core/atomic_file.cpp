#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/core.h>

#include "core/printable.hpp"
#include "core/regular_file.hpp"

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

// A chain of links longer than this is a loop (the kernel's own limit is 40).
constexpr int kMaxSymlinkHops = 40;

// Where a write to `path` lands: the file its symbolic links lead to (a relative link read
// from the link's directory), or `path` itself. A dangling link leads to the file it names,
// which the write then creates: the link stays a link either way.
Result<std::filesystem::path> write_target(const std::filesystem::path& path) {
  std::filesystem::path at = path;
  for (int hops = 0; hops <= kMaxSymlinkHops; ++hops) {
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0) {
      // A new file, or a path through a non-directory: check_target names its directory.
      if (errno == ENOENT || errno == ENOTDIR) return at;
      return io_error("cannot write", at, errno);
    }
    if (!S_ISLNK(st.st_mode)) return at;
    std::error_code ec;
    const std::filesystem::path next = std::filesystem::read_symlink(at, ec);
    if (ec) return io_error("cannot read the symbolic link", at, ec.value());
    at = next.is_absolute() || at.parent_path().empty() ? next : at.parent_path() / next;
  }
  return Error{ErrorKind::io, fmt::format("cannot write {}: more than {} symbolic links in a row (a loop?)",
                                          printable(path.string()), kMaxSymlinkHops)};
}

// `path` as the user gave it, and where a link leads if it does.
std::string shown_target(const std::filesystem::path& path, const std::filesystem::path& target) {
  if (target == path) return printable(path.string());
  return fmt::format("{} (a link to {})", printable(path.string()), printable(target.string()));
}

// The target's directory exists and may be written; the target, if it exists, is a regular
// file that is not read-only. Its stat if it exists, nullopt if it is to be created.
Result<std::optional<struct stat>> check_target(const std::filesystem::path& path,
                                                const std::filesystem::path& target) {
  const std::string name = shown_target(path, target);
  auto refuse = [&](const std::string& why) {
    return Error{ErrorKind::io, fmt::format("cannot write {}: {}", name, why)};
  };
  const std::filesystem::path dir = parent_of(target);
  struct stat dir_st {};
  if (::stat(dir.c_str(), &dir_st) != 0) {
    if (errno == ENOENT) return refuse(fmt::format("directory {} does not exist", printable(dir.string())));
    return refuse(fmt::format("directory {}: {}", printable(dir.string()), std::strerror(errno)));
  }
  if (!S_ISDIR(dir_st.st_mode))
    return refuse(fmt::format("{} is not a directory ({})", printable(dir.string()), file_type_name(dir_st.st_mode)));
  // The file is replaced by a new one made in its directory: that needs the directory's
  // write permission, whatever the file's own.
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    return refuse(fmt::format("directory {} is not writable ({})", printable(dir.string()), std::strerror(errno)));
  struct stat st {};
  if (::stat(target.c_str(), &st) != 0) {
    if (errno == ENOENT) return std::optional<struct stat>{};
    return refuse(std::strerror(errno));
  }
  if (!S_ISREG(st.st_mode)) return refuse(fmt::format("it is not a regular file ({})", file_type_name(st.st_mode)));
  // Renaming over a file needs only the directory's permission, so its mode must be asked
  // here. No write bit at all is refused even for root (access() would allow it): the mode
  // says "keep this as it is".
  if ((st.st_mode & 0222) == 0)
    return refuse(fmt::format("it is read-only (mode {:04o}); make it writable (chmod u+w) to replace it, or write "
                              "another file",
                              st.st_mode & 07777));
  if (::access(target.c_str(), W_OK) != 0)
    return refuse(fmt::format("{} (mode {:04o}, owner uid {}); allowed is a file this user may write",
                              std::strerror(errno), st.st_mode & 07777, st.st_uid));
  return std::optional<struct stat>{st};
}

}  // namespace

Status check_writable(const std::filesystem::path& path) {
  auto target = write_target(path);
  if (!target) return target.error();
  auto existing = check_target(path, *target);
  if (!existing) return existing.error();
  return Ok{};
}

Status write_file_atomically(const std::filesystem::path& path,
                             std::span<const std::uint8_t> bytes) {
  auto target = write_target(path);
  if (!target) return target.error();
  auto existing = check_target(path, *target);
  if (!existing) return existing.error();
  auto temp = *target;
  temp += fmt::format(".tmp-{}", ::getpid());
  Fd fd(::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) return io_error("cannot create", temp, errno);
  if (*existing) {
    // The new file takes the old one's place with its owner and its mode (the mode after
    // the owner: a chown clears set-id bits).
    const struct stat& old = **existing;
    if (::fchown(fd.get(), old.st_uid, old.st_gid) != 0) {
      // Only root (or the owner, to a group it is in) may give a file away: otherwise the
      // new file is the writer's, as an editor's save makes it. Not an error.
    }
    if (::fchmod(fd.get(), old.st_mode & 07777) != 0) {
      int err = errno;
      ::unlink(temp.c_str());
      return io_error("cannot set the mode of", temp, err);
    }
  }
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
  if (::rename(temp.c_str(), target->c_str()) != 0) {
    int err = errno;
    ::unlink(temp.c_str());
    return io_error("cannot rename into place", *target, err);
  }
  return fsync_directory(parent_of(*target));
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
                                            file_type_name(st.st_mode))};
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

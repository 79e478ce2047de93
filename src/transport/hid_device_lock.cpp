#include "transport/hid_device_lock.hpp"

#include <cerrno>
#include <filesystem>
#include <fstream>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.hpp"
#include "transport/fd_stream.hpp"

namespace armctl::transport {

std::vector<NodeHolder> programs_holding(const std::string& path, const std::string& proc_root) {
  namespace fs = std::filesystem;
  std::vector<NodeHolder> out;
  struct stat node {};
  if (::stat(path.c_str(), &node) != 0) return out;
  const std::string self = std::to_string(::getpid());
  std::error_code ec;
  for (const auto& proc : fs::directory_iterator(proc_root, ec)) {
    const std::string pid = proc.path().filename().string();
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos || pid == self) {
      continue;
    }
    std::error_code fd_ec;
    for (const auto& fd : fs::directory_iterator(proc.path() / "fd", fd_ec)) {
      struct stat target {};
      if (::stat(fd.path().c_str(), &target) != 0) continue;  // closed meanwhile
      if (target.st_dev != node.st_dev || target.st_ino != node.st_ino) continue;
      NodeHolder h;
      h.pid = std::stoi(pid);
      std::ifstream comm(proc.path() / "comm");
      std::getline(comm, h.program);
      if (h.program.empty()) h.program = "?";
      out.push_back(std::move(h));
      break;  // one entry per process
    }
  }
  return out;
}

std::string holders_text(const std::vector<NodeHolder>& holders) {
  std::string out;
  for (const auto& h : holders) {
    if (!out.empty()) out += ", ";
    out += h.program + " (pid " + std::to_string(h.pid) + ")";
  }
  return out;
}

NodeLock::NodeLock(const std::string& path) {
  // hidapi does not hand out its descriptor, so the lock has its own. Read-only is enough
  // for flock; the node's permissions decide as they do for hidapi. On hidraw this handle
  // gets its own copy of the reports too; it is never read, and the kernel simply stops
  // queueing for it when its small buffer is full, which costs the other handles nothing.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    const int err = errno;
    std::string msg = errno_text("open HID device", path, err);
    if (err == EACCES) {
      msg += " — install udev/50-armctl.rules and re-plug the board (see docs/usb-hid.md)";
    }
    throw ArmctlError(ErrorKind::io, msg);
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    const std::string who = holders_text(programs_holding(path));
    throw ArmctlError(ErrorKind::io,
                      errno_text("lock", path, err) + ": another program is using the board (" +
                          (who.empty() ? std::string("Linux does not tell which; try `sudo fuser -v ") +
                                             path + "`"
                                       : "held by " + who) +
                          "); stop it and try again");
  }
}

NodeLock::~NodeLock() {
  if (fd_ >= 0) ::close(fd_);  // closing drops the flock
}

}  // namespace armctl::transport

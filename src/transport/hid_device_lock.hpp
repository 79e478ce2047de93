// Exclusive use of a hidraw node. hidraw hands every open handle a copy of every input
// report, so a second program talking to the same board makes replies ambiguous (Robot
// Commands has no sequence numbers). armctl takes an advisory flock on the node, as the
// serial path does on a tty, and names whoever else has the node open, as far as Linux
// tells (/proc/PID/fd of processes this user may inspect; root sees all).
#pragma once

#include <string>
#include <vector>

namespace armctl::transport {

struct NodeHolder {
  int pid = 0;
  std::string program;  // /proc/PID/comm, e.g. "fwupd", "python3"
};

// Every process other than this one with `path` open (matched by device and inode, so
// symlinks such as /dev/xarm count). Processes whose fds we may not read are not listed.
// `proc_root` is for tests.
std::vector<NodeHolder> programs_holding(const std::string& path,
                                         const std::string& proc_root = "/proc");

// "fwupd (pid 812), python3 (pid 4410)"; "" for none.
std::string holders_text(const std::vector<NodeHolder>& holders);

// An advisory exclusive lock (flock) on `path` for as long as this object lives.
class NodeLock {
 public:
  // Throws ArmctlError(io): the node cannot be opened (errno named, udev hint on EACCES),
  // or another process holds the lock (named when Linux tells who).
  explicit NodeLock(const std::string& path);
  ~NodeLock();
  NodeLock(const NodeLock&) = delete;
  NodeLock& operator=(const NodeLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace armctl::transport

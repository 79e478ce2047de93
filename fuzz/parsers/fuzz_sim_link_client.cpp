// The master's end of the sim link (devices/joint_bus/sim_link_client.hpp) against a
// hostile "simulated arm": a thread accepts the client's connection on a unix socket,
// sends the fuzzer's bytes as everything the arm says, and hangs up. The client must
// either refuse with ArmctlError (io, timeout, protocol) or come up with a usable link
// (1..7 joints, a baud rate the bus timing can divide by), over which bus-master
// transactions then end in results or ArmctlErrors, never a crash. No real waiting: the
// hang-up ends every read at once.
#include <sys/socket.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <thread>

#include "core/error.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_bus/sim_link_client.hpp"
#include "devices/joint_bus/unix_socket.hpp"

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_sim_link_client: %s\n", what);
  std::abort();
}

struct Listener {
  std::string path = "/tmp/armctl-fuzz-sim-link-" + std::to_string(::getpid()) + ".sock";
  int fd = armctl::joint_bus::sim_link::listen_unix(path);
  ~Listener() {
    ::close(fd);
    ::unlink(path.c_str());
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl;
  static Listener listener;
  std::thread arm([&] {
    const int fd = ::accept(listener.fd, nullptr, nullptr);
    if (fd < 0) return;
    joint_bus::sim_link::send_all(fd, std::span<const std::uint8_t>(data, size));
    ::close(fd);
  });
  try {
    joint_bus::SimLinkClient link(listener.path);
    check(link.joint_count() >= 1 && link.joint_count() <= 7, "joint count 1..7");
    check(link.baud() >= 300, "a baud rate the bus timing can use (>= 300)");
    joint_bus::BusMaster master(link);
    for (int j = 1; j <= link.joint_count() && j <= 2; ++j) {
      (void)master.ping(j, 0x1234);
      (void)master.get_position(j);
    }
  } catch (const ArmctlError& e) {
    const ErrorKind k = e.error().kind;
    check(k == ErrorKind::io || k == ErrorKind::timeout || k == ErrorKind::protocol,
          "error kind io, timeout or protocol");
  }
  arm.join();
  return 0;
}

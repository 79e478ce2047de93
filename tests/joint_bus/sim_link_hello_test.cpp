// Regression found by fuzz/parsers/fuzz_sim_link_client: a simulated arm announcing baud 0
// in its hello was accepted, and the master's first transaction divided by it (SIGFPE).
// The hello's baud must be one `armctl sim scara` can run at; anything else is refused.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <thread>

#include <fmt/core.h>

#include "core/error.hpp"
#include "devices/joint_bus/sim_link_client.hpp"
#include "devices/joint_bus/sim_link_protocol.hpp"
#include "devices/joint_bus/unix_socket.hpp"

namespace armctl::test {
namespace {

namespace sim_link = joint_bus::sim_link;

// Serves one connection: sends a hello announcing `joints` and `baud`, then hangs up.
// Returns the client's error message, or "" if the client accepted the hello.
std::string connect_to_arm_saying(std::uint8_t joints, std::uint32_t baud) {
  const std::string path = fmt::format("/tmp/armctl-hello-test-{}.sock", ::getpid());
  const int listen_fd = sim_link::listen_unix(path);
  std::thread arm([&] {
    const int fd = ::accept(listen_fd, nullptr, nullptr);
    if (fd < 0) return;
    const std::array<std::uint8_t, 5> hello{joints, static_cast<std::uint8_t>(baud),
                                            static_cast<std::uint8_t>(baud >> 8),
                                            static_cast<std::uint8_t>(baud >> 16),
                                            static_cast<std::uint8_t>(baud >> 24)};
    sim_link::send_all(fd, sim_link::encode(sim_link::Type::hello, hello));
    ::close(fd);
  });
  std::string error;
  try {
    joint_bus::SimLinkClient client(path);
    EXPECT_EQ(client.baud(), baud);
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::protocol);
    error = e.what();
  }
  arm.join();
  ::close(listen_fd);
  ::unlink(path.c_str());
  return error;
}

TEST(SimLinkHello, BaudZeroIsRefusedNamingTheAllowedRange) {
  const std::string e = connect_to_arm_saying(7, 0);
  EXPECT_NE(e.find("baud 0 (allowed: 300..4000000)"), std::string::npos) << e;
}

TEST(SimLinkHello, BaudOutsideWhatAnArmCanRunAtIsRefused) {
  EXPECT_NE(connect_to_arm_saying(7, 299), "");
  EXPECT_NE(connect_to_arm_saying(7, 4000001), "");
  EXPECT_NE(connect_to_arm_saying(7, 0xFFFFFFFF), "");
}

TEST(SimLinkHello, UsualBaudRatesAreAccepted) {
  EXPECT_EQ(connect_to_arm_saying(7, 9600), "");
  EXPECT_EQ(connect_to_arm_saying(1, 115200), "");
}

}  // namespace
}  // namespace armctl::test

// Regression found by fuzz/parsers/fuzz_sim_link_client: a simulated arm announcing baud 0
// in its hello was accepted, and the master's first transaction divided by it (SIGFPE).
// The hello's baud must be one `armctl sim scara` can run at; anything else is refused.
#include <gtest/gtest.h>

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <thread>

#include <fmt/core.h>

#include "core/error.hpp"
#include "devices/joint_bus/bus_master.hpp"
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


// Regression: an arm that sent a second hello mid-session announcing fewer joints changed
// the link's joint count, and the master's next set_select for a higher joint threw
// invalid_argument. A hello after the first is a protocol error that closes the link.
std::array<std::uint8_t, 5> hello_payload(std::uint8_t joints, std::uint32_t baud) {
  return {joints, static_cast<std::uint8_t>(baud), static_cast<std::uint8_t>(baud >> 8),
          static_cast<std::uint8_t>(baud >> 16), static_cast<std::uint8_t>(baud >> 24)};
}

// Waits (bounded: a broken client must fail the test, not hang it) until `fd` is readable;
// then reads what is there. Returns the byte count, 0 at end of stream, -1 on time-out.
long read_some(int fd, std::array<std::uint8_t, 256>& buf) {
  pollfd p{fd, POLLIN, 0};
  if (::poll(&p, 1, 5000) != 1) return -1;
  return ::recv(fd, buf.data(), buf.size(), 0);
}

TEST(SimLinkHello, ASecondHelloMidSessionIsAProtocolErrorThatClosesTheLink) {
  const std::string path = fmt::format("/tmp/armctl-hello-twice-test-{}.sock", ::getpid());
  const int listen_fd = sim_link::listen_unix(path);
  bool client_hung_up = false;
  std::thread arm([&] {
    const int fd = ::accept(listen_fd, nullptr, nullptr);
    if (fd < 0) return;
    sim_link::send_all(fd, sim_link::encode(sim_link::Type::hello, hello_payload(7, 115200)));
    std::array<std::uint8_t, 256> buf{};
    if (read_some(fd, buf) > 0) {  // the master's first transaction has begun
      sim_link::send_all(fd, sim_link::encode(sim_link::Type::hello, hello_payload(2, 115200)));
      long n = 0;
      while ((n = read_some(fd, buf)) > 0) {
      }
      client_hung_up = n == 0;
    }
    ::close(fd);
  });
  {
    joint_bus::SimLinkClient link(path);
    ASSERT_EQ(link.joint_count(), 7);
    joint_bus::BusMaster master(link);
    {
      const auto r = master.ping(5, 0x1234);
      ASSERT_FALSE(r.ok()) << "a second hello was accepted";
      EXPECT_EQ(r.error().kind, ErrorKind::protocol) << r.error().message;
      EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, joint_bus::FailureKind::link);
      const std::string& m = r.error().message;
      EXPECT_NE(m.find("second hello"), std::string::npos) << m;
      EXPECT_NE(m.find("after the first hello (7 joints, 115200 baud)"), std::string::npos) << m;
    }
    EXPECT_EQ(link.joint_count(), 7) << "the first hello's joint count stands";
    // The link is closed now: the next transaction fails as io, never invalid_argument.
    {
      const auto r = master.ping(5, 0x1234);
      ASSERT_FALSE(r.ok()) << "a closed link carried a transaction";
      EXPECT_EQ(r.error().kind, ErrorKind::io) << r.error().message;
      EXPECT_NE(r.error().message.find("closed after a protocol error"), std::string::npos)
          << r.error().message;
    }
    // The arm sees the hang-up at once, before the client object is gone.
    arm.join();
    EXPECT_TRUE(client_hung_up);
  }
  ::close(listen_fd);
  ::unlink(path.c_str());
}

}  // namespace
}  // namespace armctl::test

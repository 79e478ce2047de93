// The sim link: a simulated arm served on a unix socket (real time, in a thread) and the
// master talking to it through SimLinkClient, unchanged.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <unistd.h>

#include <thread>

#include <fmt/core.h>

#include "devices/joint_bus/bus_connection.hpp"
#include "devices/joint_bus/sim_link_client.hpp"
#include "devices/joint_bus/sim_link_protocol.hpp"
#include "devices/joint_bus/sim_link_server.hpp"
#include "devices/joint_bus/unix_socket.hpp"
#include "sim_fixture.hpp"

namespace armctl::test {
namespace {

using namespace std::chrono_literals;
namespace sim_link = joint_bus::sim_link;

TEST(SimLinkProtocol, ParserSplitsMessagesAndRefusesUnknownTypes) {
  sim_link::Parser p;
  auto a = sim_link::encode(sim_link::Type::write, std::vector<std::uint8_t>{1, 2, 3});
  auto b = sim_link::encode(sim_link::Type::flush);
  p.push(std::span<const std::uint8_t>(a.data(), 3));
  EXPECT_FALSE(p.next());
  p.push(std::span<const std::uint8_t>(a.data() + 3, a.size() - 3));
  p.push(b);
  auto m1 = p.next();
  ASSERT_TRUE(m1);
  EXPECT_EQ(m1->type, sim_link::Type::write);
  EXPECT_EQ(m1->payload, (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(p.next()->type, sim_link::Type::flush);
  const std::array<std::uint8_t, 2> junk{'Z', 0};
  p.push(junk);
  EXPECT_FALSE(p.next());
  ASSERT_TRUE(p.error());
}

// Real time on a shared, loaded test machine: this test is about what crosses the socket,
// not about latency, so give each word a generous second.
joint_bus::MasterOptions relaxed(joint_bus::MasterOptions o) {
  o.timing.turnaround = 1s;
  return o;
}

class SimLinkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path = fmt::format("/tmp/armctl-simlink-test-{}.sock", ::getpid());
    server = std::make_unique<joint_bus::SimLinkServer>(arm->link(), path);
    server->set_tick([this] { arm->bus().sync(); });
    thread = std::thread([this] { server->run(); });
  }
  void TearDown() override {
    server->request_stop();
    thread.join();
    server.reset();
    EXPECT_NE(::access(path.c_str(), F_OK), 0) << "socket file left behind";
  }
  std::unique_ptr<joint_sim::SimArm> arm = make_arm(115200);
  std::string path;
  std::unique_ptr<joint_bus::SimLinkServer> server;
  std::thread thread;
};

TEST_F(SimLinkTest, MasterRunsUnchangedOverTheSocketAndStateSurvivesReconnects) {
  {
    auto conn = joint_bus::open_bus(joint_bus::UnixDevice{path}).value();
    joint_bus::BusMaster m(conn->link(), relaxed(conn->default_options()));
    EXPECT_EQ(m.joint_count(), 7);
    EXPECT_EQ(conn->link().baud(), 115200u);
    EXPECT_EQ(m.ping(3, 4321).value(), 4321);
    auto moved = m.drive_to(5, 777);
    ASSERT_TRUE(moved.ok()) << moved.error().message;
    EXPECT_EQ(joint_bus::joint_failure(m.transact(2, 99, std::nullopt).error())->code(), 930);
  }
  {  // a second master sees the state the first left
    auto conn = joint_bus::open_bus(joint_bus::UnixDevice{path}).value();
    joint_bus::BusMaster m(conn->link(), relaxed(conn->default_options()));
    EXPECT_EQ(m.get_target(5).value(), 777);
    auto all = m.for_each_joint<std::int16_t>([&](int j) { return m.get_joint_number(j); });
    for (const auto& o : all) EXPECT_EQ(o.result.value(), o.joint);
  }
}

TEST_F(SimLinkTest, ClientThatLeavesMidTransactionLeavesNoJointSelected) {
  {
    joint_bus::SimLinkClient c(path);
    c.set_select(4, true);
    ASSERT_TRUE(c.read_byte(c.clock().now() + 1s).has_value());  // READY starts
  }
  joint_bus::SimLinkClient c2(path);
  joint_bus::BusMaster m(c2, relaxed({}));
  EXPECT_EQ(m.get_joint_number(4).value(), 4);
}

TEST_F(SimLinkTest, BadMessageIsRefusedAndTheConnectionDropped) {
  const int fd = sim_link::connect_unix(path);
  const std::array<std::uint8_t, 4> bad{'S', 2, 9, 1};  // joint 9
  ASSERT_TRUE(sim_link::send_all(fd, bad));
  std::vector<std::uint8_t> got;
  SteadyClock clock;
  const TimePoint until = clock.now() + 2s;
  std::array<std::uint8_t, 256> buf{};
  for (;;) {
    const long n = sim_link::receive_some(fd, buf, until, clock);
    if (n <= 0) break;
    got.insert(got.end(), buf.begin(), buf.begin() + n);
  }
  ::close(fd);
  const std::string text(got.begin(), got.end());
  EXPECT_NE(text.find("joint 1..7"), std::string::npos) << text;
  EXPECT_EQ(server->stats().protocol_errors, 1u);
}

TEST(SimLinkClient, NoArmListeningIsAClearError) {
  try {
    joint_bus::SimLinkClient c("/tmp/armctl-nobody-listens-here.sock");
    FAIL();
  } catch (const ArmctlError& e) {
    EXPECT_NE(std::string(e.what()).find("armctl sim scara"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace armctl::test

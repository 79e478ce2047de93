// The real-hardware link (serial port + select lines) as far as a pty and fake GPIO lines
// allow: a test thread plays the joints on the pty's other side, seeing the select edges
// the master makes through FakeSelectLines. Real clock: timeouts use poll().
#include <gtest/gtest.h>

#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#include "devices/joint_bus/bus_master.hpp"
#include "portable/joint_bus_codes.hpp"
#include "transport/fake_select_lines.hpp"
#include "transport/gpiod_select_lines.hpp"
#include "transport/pty.hpp"
#include "transport/serial_joint_bus_link.hpp"
#include "transport/serial_port.hpp"

namespace armctl::test {
namespace {

using namespace std::chrono_literals;

// Select edges, handed from the master's thread to the joints' thread.
class EdgeQueue {
 public:
  void push(int joint, bool high) {
    {
      std::lock_guard lock(mutex_);
      edges_.push_back({joint, high});
    }
    cv_.notify_one();
  }
  std::optional<transport::FakeSelectLines::Edge> pop(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    if (!cv_.wait_for(lock, wait, [&] { return !edges_.empty(); })) return std::nullopt;
    auto e = edges_.front();
    edges_.pop_front();
    return e;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<transport::FakeSelectLines::Edge> edges_;
};

// Joints 1..7 on the far side of the pty; `dead` never answers. Each joint keeps a target.
class JointPlayer {
 public:
  JointPlayer(transport::FdStream& wire, EdgeQueue& edges, int dead) : wire_(wire), edges_(edges), dead_(dead) {
    thread_ = std::thread([this] { run(); });
  }
  ~JointPlayer() {
    stop_ = true;
    thread_.join();
  }
  std::int16_t target(int j) {
    std::lock_guard lock(mutex_);
    return targets_[static_cast<std::size_t>(j)];
  }

 private:
  std::optional<std::int16_t> read_word() {
    std::array<std::uint8_t, 2> b{};
    std::size_t got = 0;
    const TimePoint deadline = wire_.clock().now() + 500ms;
    while (got < 2) {
      const std::size_t n = wire_.read(std::span<std::uint8_t>(b.data() + got, 2 - got), deadline);
      if (n == 0) return std::nullopt;
      got += n;
    }
    return joint_bus::word_from(b[0], b[1]);
  }
  void send(std::int16_t w) {
    const std::array<std::uint8_t, 2> b{joint_bus::word_low(w), joint_bus::word_high(w)};
    wire_.write(b);
  }
  void run() {
    while (!stop_) {
      auto e = edges_.pop(20ms);
      if (!e || !e->high) continue;
      const int j = e->joint;
      if (j == dead_) continue;
      send(static_cast<std::int16_t>(j));  // READY
      auto cmd = read_word();
      if (!cmd) continue;
      const auto shape = joint_bus::command_shape(*cmd);
      std::optional<std::int16_t> data;
      if (shape.takes_data) data = read_word();
      std::int16_t status = joint_bus::success_status(*cmd);
      {
        std::lock_guard lock(mutex_);
        auto& t = targets_[static_cast<std::size_t>(j)];
        if (*cmd == joint_bus::cmd_ping) send(*data);
        if (*cmd == joint_bus::cmd_get_joint_number) send(static_cast<std::int16_t>(j));
        if (*cmd == joint_bus::cmd_get_target) send(t);
        if (*cmd == joint_bus::cmd_drive_to) t = *data;
        if (!shape.known) status = joint_bus::status_unknown_command;
      }
      auto low = edges_.pop(500ms);  // STATUS only after select falls
      if (low && !low->high) send(status);
    }
  }

  transport::FdStream& wire_;
  EdgeQueue& edges_;
  int dead_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::array<std::int16_t, 8> targets_{};
  std::thread thread_;
};

TEST(SerialJointBusLink, MasterTalksToJointsOverAPtyWithFakeSelectLines) {
  transport::Pty pty = transport::Pty::open();
  EdgeQueue edges;
  auto lines = std::make_unique<transport::FakeSelectLines>(7, [&](int j, bool high) { edges.push(j, high); });
  transport::FakeSelectLines* lines_view = lines.get();
  auto port = transport::SerialPort::open(pty.slave_path(), 115200);
  transport::SerialJointBusLink link(std::move(port), std::move(lines), 115200);
  JointPlayer joints(pty.master(), edges, /*dead=*/6);

  joint_bus::MasterOptions o;
  o.timing.turnaround = 100ms;  // a test thread on a shared machine, not a microcontroller
  joint_bus::BusMaster m(link, o);
  EXPECT_EQ(m.joint_count(), 7);
  EXPECT_EQ(m.ping(3, 1234).value(), 1234);
  EXPECT_EQ(m.get_joint_number(7).value(), 7);
  ASSERT_TRUE(m.drive_to(2, -500).ok());
  EXPECT_EQ(joints.target(2), -500);
  EXPECT_EQ(m.get_target(2).value(), -500);
  EXPECT_EQ(joint_bus::joint_failure(m.transact(1, 99, std::nullopt).error())->code(), 930);

  auto dead = m.get_target(6);
  ASSERT_FALSE(dead.ok());
  EXPECT_EQ(joint_bus::joint_failure(dead.error())->code(), 990);
  EXPECT_EQ(m.ping(4, -2).value(), -2);  // the others still answer

  for (int j = 1; j <= 7; ++j) EXPECT_FALSE(lines_view->level(j)) << j;
  const auto all = lines_view->edges();
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front().joint, 3);
  EXPECT_TRUE(all.front().high);
  EXPECT_EQ(all.size() % 2, 0u);  // every raise has its drop
}

TEST(SerialJointBusLink, DrainDiscardsStaleBytes) {
  transport::Pty pty = transport::Pty::open();
  auto port = transport::SerialPort::open(pty.slave_path(), 9600);
  transport::SerialJointBusLink link(std::move(port), std::make_unique<transport::FakeSelectLines>(2), 9600);
  const std::array<std::uint8_t, 3> junk{1, 2, 3};
  pty.master().write(junk);
  const TimePoint until = link.clock().now() + 2s;
  while (link.drain() == 0 && link.clock().now() < until) {
    std::this_thread::yield();  // the bytes cross the pty asynchronously; no fixed sleep
  }
  EXPECT_FALSE(link.read_byte(link.clock().now() + 20ms).has_value());
}

TEST(FakeSelectLines, RefusesJointsOutsideItsCount) {
  transport::FakeSelectLines lines(3);
  EXPECT_THROW(lines.set(0, true), ArmctlError);
  EXPECT_THROW(lines.set(4, true), ArmctlError);
  lines.set(2, true);
  lines.set(2, true);  // same level: no edge
  EXPECT_EQ(lines.edges().size(), 1u);
}

TEST(GpiodSelectLines, MissingChipIsAClearIoError) {
  try {
    transport::GpiodSelectLines::open("armctl-no-such-chip", {17});
    FAIL() << "opened a chip that does not exist";
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::io);
    EXPECT_NE(std::string(e.what()).find("armctl-no-such-chip"), std::string::npos);
  }
}

}  // namespace
}  // namespace armctl::test

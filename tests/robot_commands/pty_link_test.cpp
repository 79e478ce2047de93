// Real byte pipes: serial port on a pty (termios settings, errors, exclusive open), the SDK
// over a pty against a scripted fake board, and against the board helper's emulator
// (EmulatorRunner) on a pty. These use the steady clock; timeouts only bound failures.
#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "devices/robot_commands/client.hpp"
#include "devices/robot_commands/device_uri.hpp"
#include "devices/robot_commands/stream_link.hpp"
#include "devices/xarm_emulator/emulator_runner.hpp"
#include "protocol/robot_commands/frame_receiver.hpp"
#include "protocol/robot_commands/messages.hpp"
#include "transport/pty.hpp"
#include "transport/serial_port.hpp"

namespace armctl::robot_commands {
namespace {

using namespace std::chrono_literals;

TEST(SerialPort, RefusesNonStandardBaudAndNamesThePath) {
  try {
    transport::SerialPort::open("/dev/null", 12345);
    FAIL();
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::invalid_argument);
    EXPECT_NE(std::string(e.what()).find("115200"), std::string::npos);
  }
  try {
    transport::SerialPort::open("/dev/armctl-no-such-port");
    FAIL();
  } catch (const ArmctlError& e) {
    EXPECT_EQ(e.error().kind, ErrorKind::io);
    EXPECT_NE(std::string(e.what()).find("/dev/armctl-no-such-port"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("errno 2"), std::string::npos);
  }
}

TEST(SerialPort, PtyCarriesEveryByteValueBothWaysAndOpenIsExclusive) {
  auto pty = transport::Pty::open();
  auto port = transport::SerialPort::open(pty.slave_path(), 115200);
  EXPECT_THROW(transport::SerialPort::open(pty.slave_path()), ArmctlError);  // exclusive
  std::vector<std::uint8_t> all(256);
  for (int i = 0; i < 256; ++i) all[i] = static_cast<std::uint8_t>(i);
  port->write(all);
  std::vector<std::uint8_t> got;
  const auto deadline = port->clock().now() + 2s;
  while (got.size() < all.size()) {
    std::array<std::uint8_t, 512> buf{};
    const auto n = pty.master().read(buf, deadline);
    ASSERT_GT(n, 0u) << "timed out after " << got.size() << " bytes";
    got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  }
  EXPECT_EQ(got, all);  // raw: no CR/LF translation, no flow-control bytes eaten
  pty.master().write(all);
  got.clear();
  while (got.size() < all.size()) {
    std::array<std::uint8_t, 512> buf{};
    const auto n = port->read(buf, deadline);
    ASSERT_GT(n, 0u);
    got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  }
  EXPECT_EQ(got, all);
  // Nothing more: a read times out at its deadline.
  std::array<std::uint8_t, 8> buf{};
  EXPECT_EQ(port->read(buf, port->clock().now() + 20ms), 0u);
  port.reset();
  EXPECT_NO_THROW(transport::SerialPort::open(pty.slave_path()));  // released on close
}

TEST(DeviceUri, Forms) {
  auto a = parse_device_uri("hid");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->kind, DeviceUri::Kind::hid);
  EXPECT_EQ(a->target, "");
  EXPECT_EQ(parse_device_uri("hid:ABC123")->target, "ABC123");
  EXPECT_EQ(parse_device_uri("hid:/dev/hidraw2")->target, "/dev/hidraw2");
  auto s = parse_device_uri("serial:/dev/ttyUSB0?baud=115200");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->kind, DeviceUri::Kind::serial);
  EXPECT_EQ(s->target, "/dev/ttyUSB0");
  EXPECT_EQ(s->baud, 115200u);
  EXPECT_EQ(parse_device_uri("/dev/ttyACM0")->baud, 9600u);
  EXPECT_FALSE(parse_device_uri("hid:"));
  EXPECT_FALSE(parse_device_uri("ttyUSB0"));
  EXPECT_FALSE(parse_device_uri("serial:/dev/ttyUSB0?baud=1234"));
  EXPECT_FALSE(parse_device_uri("serial:/dev/ttyUSB0?parity=odd"));
  EXPECT_NE(parse_device_uri("tcp:1.2.3.4").error().message.find("allowed"), std::string::npos);
}

// sim?miscal=SEED (core/miscalibration.hpp): a whole number, named with its value in errors;
// only the simulator takes it.
TEST(DeviceUri, SimTakesAMiscalSeed) {
  EXPECT_FALSE(parse_device_uri("sim")->miscal.has_value());
  const auto m = parse_device_uri("sim?miscal=42");
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_EQ(m->kind, DeviceUri::Kind::sim);
  EXPECT_EQ(m->miscal, 42u);
  for (const char* bad : {"sim?miscal=", "sim?miscal=abc", "sim?miscal=-1", "sim?miscal=99999999999"}) {
    const auto r = parse_device_uri(bad);
    ASSERT_FALSE(r) << bad;
    EXPECT_EQ(r.error().kind, ErrorKind::invalid_argument) << bad;
    const std::string value = std::string(bad).substr(std::string("sim?miscal=").size());
    EXPECT_NE(r.error().message.find("miscal '" + value + "' is not a seed (allowed: a whole number 0..4294967295)"),
              std::string::npos)
        << r.error().message;
  }
  for (const char* other : {"sim?seed=3", "hid?miscal=3", "serial:/dev/ttyUSB0?miscal=3"}) {
    const auto r = parse_device_uri(other);
    ASSERT_FALSE(r) << other;
    EXPECT_NE(r.error().message.find("unknown option"), std::string::npos) << r.error().message;
  }
}

// A fake board on the pty master: answers GetBatteryVoltage and ServoPositionRead, and
// sends a group-started notification plus garbage before each battery reply.
class ScriptedPtyBoard {
 public:
  ScriptedPtyBoard() : pty_(transport::Pty::open()) {
    thread_ = std::thread([this] { serve(); });
  }
  ~ScriptedPtyBoard() {
    stop_ = true;
    thread_.join();
  }
  const std::string& path() const { return pty_.slave_path(); }

 private:
  void send(const rc::Frame& f) { pty_.master().write(rc::encode_frame(f)); }
  void serve() {
    rc::FrameReceiver rx;
    while (!stop_) {
      std::array<std::uint8_t, 256> buf{};
      const auto n = pty_.master().read(buf, pty_.master().clock().now() + 20ms);
      rx.feed(std::span<const std::uint8_t>(buf.data(), n));
      while (auto f = rx.next()) {
        if (f->cmd == 15) {
          send(rc::Frame{6, {1, 2, 0}});
          pty_.master().write(std::vector<std::uint8_t>{0x00, 0x13, 0x55});
          send(rc::Frame{15, {0x4C, 0x1D}});
        } else if (f->cmd == 21) {
          rc::ServoPositionReply r;
          for (std::size_t i = 1; i < f->data.size(); ++i) {
            r.positions.push_back({f->data[i], static_cast<std::int16_t>(100 * f->data[i])});
          }
          send(rc::encode(rc::BoardMessage{r}).value());
        }
      }
    }
  }
  transport::Pty pty_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// A board that stops reading (here: nobody reads the pty) fills the line's buffer; the SDK
// then returns a timeout instead of hanging in write.
TEST(ClientOverPty, ABoardThatStopsReadingIsATimeoutNotAHang) {
  auto pty = transport::Pty::open();
  auto port = transport::SerialPort::open(pty.slave_path());
  port->set_write_timeout(100ms);
  StreamLink link(std::move(port), "serial:" + pty.slave_path());
  Client c(link);
  Status s = Ok{};
  int moves = 0;
  while (s && moves < 1'000'000) {
    s = c.move({{1, static_cast<std::uint16_t>(moves % 1000)}}, 100);
    ++moves;
  }
  ASSERT_FALSE(s) << "a million frames went into a pty nobody reads";
  EXPECT_EQ(s.error().kind, ErrorKind::timeout) << s.error().message;
  EXPECT_NE(s.error().message.find(pty.slave_path()), std::string::npos) << s.error().message;
  EXPECT_GT(moves, 1) << "the first frames fit in the buffer";
}

TEST(ClientOverPty, ScriptedFakeBoard) {
  ScriptedPtyBoard board;
  auto link = open_link(parse_device_uri("serial:" + board.path()).value()).value();
  Client c(*link, ClientOptions{.reply_timeout = 2s});
  auto mv = c.battery_millivolts();
  ASSERT_TRUE(mv) << mv.error().message;
  EXPECT_EQ(*mv, 7500);
  auto e = c.next_event();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->kind, GroupEventKind::started);
  EXPECT_EQ(e->group, 1);
  auto p = c.read_positions({2, 5});
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ((*p)[1].position, 500);
  EXPECT_GE(link->discarded(), 2u);  // the garbage between frames was skipped
}

TEST(ClientOverPty, EmulatedXarmEveryCommand) {
  xarm::EmulatorRunner runner(xarm::EmulatorRunnerOptions{});
  runner.start();
  auto link = open_link(parse_device_uri(runner.device_path() + "?baud=115200").value()).value();
  Client c(*link, ClientOptions{.reply_timeout = 2s, .download_timeout = 2s});
  ASSERT_TRUE(c.move({{1, 200}, {4, 800}}, 0));
  ASSERT_TRUE(c.pump_events(c.clock().now() + 300ms));  // the emulator's fastest move is not instant
  auto p = c.read_positions({1, 4});
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ((*p)[0].position, 200);
  EXPECT_EQ((*p)[1].position, 800);
  ASSERT_TRUE(c.servos_off({1}));
  ASSERT_TRUE(c.battery_millivolts());
  ASSERT_TRUE(c.adjust_offset(2, 15));
  auto o = c.read_offsets({2});
  ASSERT_TRUE(o) << o.error().message;
  EXPECT_EQ((*o)[0].offset, 15);
  ASSERT_TRUE(c.save_offsets({2}));
  ASSERT_TRUE(c.set_mode(3, ServoMode::servo, 0));
  ASSERT_TRUE(c.write_bus_servo_info(BusServoInfoWrite{1, 0, 1000, 4500, 12000, 85, 0, 3}));
  auto info = c.read_bus_servo_info();
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->led_warning, 3);
  ASSERT_TRUE(c.download_group(1, {{50, {{1, 300}}}, {50, {{1, 700}}}}));
  ASSERT_TRUE(c.set_group_speed(1, 100));
  ASSERT_TRUE(c.run_group(1, 1));
  auto started = c.wait_event(c.clock().now() + 2s);
  ASSERT_TRUE(started);
  EXPECT_EQ(started->kind, GroupEventKind::started);
  auto finished = c.wait_event(c.clock().now() + 5s);
  ASSERT_TRUE(finished);
  EXPECT_EQ(finished->kind, GroupEventKind::finished);
  ASSERT_TRUE(c.run_group(1, 0));
  ASSERT_TRUE(c.wait_event(c.clock().now() + 2s));
  ASSERT_TRUE(c.stop_group());
  auto stopped = c.wait_event(c.clock().now() + 2s);
  ASSERT_TRUE(stopped);
  EXPECT_EQ(stopped->kind, GroupEventKind::stopped);
  ASSERT_TRUE(c.erase_group(1));
  runner.stop();
  EXPECT_EQ(runner.stats().ignored(), 0u);
}

}  // namespace
}  // namespace armctl::robot_commands

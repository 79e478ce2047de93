// The emulator served on a real pty, opened by the host side with transport::SerialPort.
#include "harness.hpp"

#include "devices/xarm_emulator/emulator_runner.hpp"
#include "transport/serial_port.hpp"

namespace armctl::xarm::test {
namespace {

// Reads one complete frame (or fails after `timeout`; only a bound, never a pacing sleep).
std::optional<rc::Frame> read_frame(transport::SerialPort& port, rc::FrameReceiver& rx,
                                    Duration timeout = std::chrono::seconds(5)) {
  TimePoint deadline = port.clock().now() + timeout;
  while (rx.pending_frames() == 0) {
    std::uint8_t buffer[64];
    std::size_t n = port.read(buffer, deadline);
    if (n == 0) return std::nullopt;
    rx.feed(std::span(buffer, n));
  }
  return rx.next();
}

TEST(EmulatorRunner, ServesCommandsOverAPty) {
  EmulatorRunner runner({});
  runner.start();
  auto port = transport::SerialPort::open(runner.device_path(), 9600);
  rc::FrameReceiver rx;

  port->write(hex("AA 55"));  // garbage first: skipped
  port->write(vector_bytes("GetBatteryVoltage"));
  auto reply = read_frame(*port, rx);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(to_hex(rc::encode_frame(*reply)),
            to_hex(vector_bytes("GetBatteryVoltage reply 7500 mV")));

  port->write(vector_bytes("ServoOffsetAdjust servo 4 by -20"));
  port->write(rc::encode_frame(*rc::encode(rc::ServoOffsetAdjust{3, 10}, rc::ServoRange::xarm())));
  port->write(vector_bytes("ServoOffsetRead servos 3, 4"));
  reply = read_frame(*port, rx);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(to_hex(rc::encode_frame(*reply)),
            to_hex(vector_bytes("ServoOffsetRead reply (+10, -20)")));

  port->write(vector_bytes("GroupErase all"));
  reply = read_frame(*port, rx);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(*reply, (rc::Frame{8, {}}));

  auto stats = runner.stats();
  EXPECT_EQ(stats.discarded_bytes, 2u);  // AA and a lone 55 before 55 55
  EXPECT_EQ(stats.handled, 5u);
  runner.stop();
}

TEST(EmulatorRunner, GroupNotificationsArriveInRealTime) {
  EmulatorRunner runner({});
  runner.start();
  auto port = transport::SerialPort::open(runner.device_path(), 115200);
  rc::FrameReceiver rx;
  auto send = [&](const rc::Request& r) {
    port->write(rc::encode_frame(*rc::encode(r, rc::ServoRange::xarm())));
  };
  send(rc::GroupDownloadBegin{0, 2});
  send(rc::GroupDownloadServoCount{0, 1});
  send(rc::GroupDownloadBlocks{0, 1});
  send(rc::GroupDownloadAction{0, 0, 0, 20, {{1, 510}}});
  send(rc::GroupDownloadAction{0, 0, 1, 20, {{1, 500}}});
  send(rc::GroupDownloadEnd{0});
  for (int frame = 0; frame < 6; ++frame) {  // sub 1, 2, 3, 4, 4, 5
    auto ack = read_frame(*port, rx);
    ASSERT_TRUE(ack.has_value());
    EXPECT_EQ(ack->cmd, 5);
  }
  send(rc::GroupRun{0, 2});
  auto started = read_frame(*port, rx);
  auto finished = read_frame(*port, rx);
  ASSERT_TRUE(started && finished);
  EXPECT_EQ(*started, (rc::Frame{6, {0, 2, 0}}));
  EXPECT_EQ(*finished, (rc::Frame{8, {0, 2, 0}}));
}

TEST(EmulatorRunner, WireTimingMakesRepliesNoFasterThanTheLine) {
  EmulatorRunnerOptions options;
  options.wire_timing = true;
  options.baud = 9600;
  EmulatorRunner runner(options);
  runner.start();
  auto port = transport::SerialPort::open(runner.device_path(), 9600);
  rc::FrameReceiver rx;
  auto request = vector_bytes("GetBatteryVoltage");
  SteadyClock clock;
  TimePoint t0 = clock.now();
  port->write(request);
  auto reply = read_frame(*port, rx);
  Duration took = clock.now() - t0;
  ASSERT_TRUE(reply.has_value());
  // 4 bytes in and 6 bytes out at 9600 8N1: at least 10 x 1.04 ms.
  EXPECT_GE(took, wire_time(4 + 6, 9600));
}

TEST(EmulatorRunner, BadBaudIsAClearError) {
  EmulatorRunnerOptions options;
  options.wire_timing = true;
  options.baud = 12345;
  try {
    EmulatorRunner runner(options);
    FAIL();
  } catch (const ArmctlError& e) {
    EXPECT_NE(std::string(e.what()).find("12345"), std::string::npos);
  }
}

}  // namespace
}  // namespace armctl::xarm::test

// The one parser of device URI text (transport/device_uri_parts.hpp), and the three device
// families that use it agreeing on what a serial port URI means.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "devices/arm_controller/controller_runner.hpp"
#include "devices/joint_bus/device_uri.hpp"
#include "devices/robot_commands/device_uri.hpp"
#include "transport/device_uri_parts.hpp"

namespace armctl::test {
namespace {

using transport::split_uri;

TEST(UriParts, SplitsKindPathAndOptions) {
  auto a = split_uri("serial:/dev/ttyUSB0?baud=115200&select=1,2");
  ASSERT_TRUE(a) << a.error().message;
  EXPECT_EQ(a->kind, "serial");
  EXPECT_EQ(a->path, "/dev/ttyUSB0");
  EXPECT_TRUE(a->has_path);
  EXPECT_TRUE(a->has_query);
  EXPECT_EQ(a->options.at("baud"), "115200");
  EXPECT_EQ(a->options.at("select"), "1,2");

  auto bare = split_uri("/dev/ttyACM0");
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->kind, "serial");
  EXPECT_EQ(bare->path, "/dev/ttyACM0");
  EXPECT_FALSE(bare->has_query);

  auto sim = split_uri("sim");
  ASSERT_TRUE(sim);
  EXPECT_EQ(sim->kind, "sim");
  EXPECT_FALSE(sim->has_path);
  EXPECT_TRUE(sim->options.empty());

  auto hid = split_uri("hid:");
  ASSERT_TRUE(hid);
  EXPECT_TRUE(hid->has_path);
  EXPECT_EQ(hid->path, "");
}

TEST(UriParts, RefusesMalformedOptions) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"sim?baud", "option 'baud' is not key=value"},
      {"sim?=3", "option '=3' is not key=value"},
      {"sim?baud=1&baud=2", "option 'baud' given twice"},
      {"sim?baud=9600&", "option '' is not key=value"},
  };
  for (const auto& [text, why] : bad) {
    auto r = split_uri(text);
    ASSERT_FALSE(r) << text;
    EXPECT_EQ(r.error().kind, ErrorKind::invalid_argument);
    EXPECT_NE(r.error().message.find(why), std::string::npos) << text << ": " << r.error().message;
  }
}

TEST(UriParts, SerialPortForms) {
  auto s = transport::parse_serial_uri(split_uri("serial:/dev/ttyS1?baud=57600").value(), 9600);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->path, "/dev/ttyS1");
  EXPECT_EQ(s->baud, 57600u);
  EXPECT_EQ(transport::parse_serial_uri(split_uri("/dev/ttyS1").value(), 9600)->baud, 9600u);
  auto extra = transport::parse_serial_uri(split_uri("/dev/x?chip=g&baud=9600").value(), 9600, {"chip"});
  ASSERT_TRUE(extra);
  EXPECT_EQ(extra->options.at("chip"), "g");
  EXPECT_FALSE(extra->options.contains("baud"));

  const std::vector<std::pair<std::string, std::string>> bad = {
      {"serial:ttyS1", "absolute device path"},
      {"serial:", "absolute device path"},
      {"serial:/dev/ttyS1?baud=1234", "baud 1234 is not a standard rate"},
      {"serial:/dev/ttyS1?baud=fast", "baud 'fast' is not a whole number"},
      {"serial:/dev/ttyS1?baud=", "baud '' is not a whole number"},
      {"serial:/dev/ttyS1?parity=odd", "unknown option 'parity' (this device takes: baud)"},
      {"hid:/dev/hidraw0", "'hid' is not a serial port"},
  };
  for (const auto& [text, why] : bad) {
    auto r = transport::parse_serial_uri(split_uri(text).value(), 9600);
    ASSERT_FALSE(r) << text;
    EXPECT_NE(r.error().message.find(why), std::string::npos) << text << ": " << r.error().message;
  }
}

TEST(UriParts, CheckOptionsNamesWhatIsAllowed) {
  EXPECT_TRUE(transport::check_options(split_uri("sim?baud=1").value(), {"baud", "config"}));
  auto r = transport::check_options(split_uri("sim?speed=1").value(), {"baud", "config"});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("unknown option 'speed' (this device takes: baud, config)"), std::string::npos);
  auto none = transport::check_options(split_uri("pty?x=1").value(), {});
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("pty takes no options"), std::string::npos);
}

// The joint bus (`--bus`, `armctl bus --device`), Robot Commands (`armctl xarm --device`) and
// the arm controller's upstream (`--upstream`) read the same serial text the same way, or
// refuse it for the same reason.
TEST(UriParts, EveryDeviceFamilyReadsSerialPortsAlike) {
  struct Case {
    std::string text;
    std::string path;  // empty: refused
    std::uint32_t baud = 0;
    std::string why;
  };
  const std::vector<Case> cases = {
      {"serial:/dev/ttyUSB0", "/dev/ttyUSB0", 9600, ""},
      {"serial:/dev/ttyUSB0?baud=115200", "/dev/ttyUSB0", 115200, ""},
      {"/dev/ttyAMA0?baud=57600", "/dev/ttyAMA0", 57600, ""},
      {"serial:/dev/ttyUSB0?baud=12345", "", 0, "baud 12345 is not a standard rate"},
      {"serial:/dev/ttyUSB0?baud=x", "", 0, "baud 'x' is not a whole number"},
      {"serial:/dev/ttyUSB0?baud=9600&baud=9600", "", 0, "option 'baud' given twice"},
      {"serial:dev/ttyUSB0", "", 0, "absolute device path"},
  };
  for (const Case& c : cases) {
    // The joint bus needs select lines as well; they do not change how the port is read.
    const std::string bus_text = c.text + (c.text.find('?') == std::string::npos ? "?" : "&") + "select=5";
    auto rc = robot_commands::parse_device_uri(c.text);
    if (c.path.empty()) {
      ASSERT_FALSE(rc) << c.text;
      EXPECT_NE(rc.error().message.find(c.why), std::string::npos) << rc.error().message;
      const auto bus = joint_bus::parse_device_uri(bus_text);
      EXPECT_FALSE(bus) << "joint bus accepted " << bus_text;
      if (!bus) {
        EXPECT_NE(bus.error().message.find(c.why), std::string::npos) << bus.error().message;
      }
      try {
        arm_controller::parse_upstream(c.text);
        ADD_FAILURE() << "upstream accepted " << c.text;
      } catch (const ArmctlError& e) {
        EXPECT_NE(std::string(e.what()).find(c.why), std::string::npos) << e.what();
      }
      continue;
    }
    ASSERT_TRUE(rc) << c.text << ": " << rc.error().message;
    EXPECT_EQ(rc->kind, robot_commands::DeviceUri::Kind::serial);
    EXPECT_EQ(rc->target, c.path);
    EXPECT_EQ(rc->baud, c.baud);
    const auto bus = std::get<joint_bus::SerialDevice>(joint_bus::parse_device_uri(bus_text).value());
    EXPECT_EQ(bus.path, c.path);
    EXPECT_EQ(bus.baud, c.baud);
    const auto up = arm_controller::parse_upstream(c.text);
    EXPECT_FALSE(up.pty);
    EXPECT_EQ(up.path, c.path);
    EXPECT_EQ(up.baud, c.baud);
  }
}

}  // namespace
}  // namespace armctl::test

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "devices/joint_bus/device_uri.hpp"

namespace armctl::test {
namespace {

using namespace joint_bus;

TEST(DeviceUri, AcceptsTheThreeForms) {
  EXPECT_FALSE(std::get<SimDevice>(parse_device_uri("sim").value()).baud.has_value());
  EXPECT_EQ(std::get<SimDevice>(parse_device_uri("sim?baud=115200").value()).baud, 115200u);
  EXPECT_EQ(std::get<SimDevice>(parse_device_uri("sim?dead=2,6").value()).dead_joints, (std::vector<int>{2, 6}));
  EXPECT_EQ(std::get<SimDevice>(parse_device_uri("sim?swapped=3").value()).swapped_joints, (std::vector<int>{3}));
  EXPECT_EQ(std::get<UnixDevice>(parse_device_uri("unix:/tmp/a.sock").value()).path, "/tmp/a.sock");
  EXPECT_EQ(std::get<SimDevice>(parse_device_uri("sim").value()).dialect, Dialect::standard);
  EXPECT_EQ(std::get<SimDevice>(parse_device_uri("sim?dialect=legacy").value()).dialect, Dialect::legacy);
  const auto s = std::get<SerialDevice>(
      parse_device_uri("serial:/dev/ttyAMA0?baud=115200&chip=gpiochip0&select=17,27,22,5,6,13,19&dialect=legacy").value());
  EXPECT_EQ(s.path, "/dev/ttyAMA0");
  EXPECT_EQ(s.baud, 115200u);
  EXPECT_EQ(s.chip, "gpiochip0");
  EXPECT_EQ(s.select, (std::vector<unsigned>{17, 27, 22, 5, 6, 13, 19}));
  EXPECT_EQ(s.dialect, Dialect::legacy);
  const auto d = std::get<SerialDevice>(parse_device_uri("serial:/dev/ttyUSB0?select=4").value());
  EXPECT_EQ(d.baud, 9600u);
  EXPECT_EQ(d.chip, "gpiochip0");
  EXPECT_EQ(d.dialect, Dialect::standard);
}

// miscal=SEED (core/miscalibration.hpp): a whole number, named with its value in errors.
TEST(DeviceUri, MiscalTakesASeed) {
  EXPECT_FALSE(std::get<SimDevice>(parse_device_uri("sim").value()).miscal.has_value());
  EXPECT_EQ(std::get<SimDevice>(parse_device_uri("sim?miscal=0").value()).miscal, 0u);
  EXPECT_EQ(std::get<SimDevice>(parse_device_uri("sim?baud=115200&miscal=4294967295").value()).miscal, 4294967295u);
  EXPECT_EQ(describe(parse_device_uri("sim?miscal=7").value()), "embedded simulated arm, mis-assembled");
  for (const char* bad : {"sim?miscal=", "sim?miscal=x", "sim?miscal=-3", "sim?miscal=4294967296", "sim?miscal=2.5"}) {
    const auto r = parse_device_uri(bad);
    ASSERT_FALSE(r) << bad;
    EXPECT_EQ(r.error().kind, ErrorKind::invalid_argument) << bad;
    const std::string value = std::string(bad).substr(std::string("sim?miscal=").size());
    EXPECT_NE(r.error().message.find("miscal '" + value + "' is not a seed (allowed: a whole number 0..4294967295)"),
              std::string::npos)
        << r.error().message;
    EXPECT_NE(r.error().message.find("sim?baud=N&config=FILE&dead=J[,J...]&dialect=legacy&miscal=SEED"),
              std::string::npos)
        << r.error().message;
  }
  EXPECT_FALSE(parse_device_uri("serial:/dev/ttyAMA0?select=1&miscal=3"));  // simulators only
  EXPECT_FALSE(parse_device_uri("unix:/a?miscal=3"));
}

TEST(DeviceUri, RefusesBadInputWithAMessageNamingIt) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"", "unknown kind"},
      {"tcp:1.2.3.4", "unknown kind"},
      {"sim?baud=12345", "not a standard rate"},
      {"sim?speed=1", "unknown option 'speed'"},
      {"sim?dialect=mega", "dialect 'mega' is neither standard nor legacy"},
      {"sim?dead=9", "dead joint '9' is not a joint (allowed 1..7"},
      {"sim?dead=0", "dead joint '0' is not a joint (allowed 1..7"},
      {"sim?dead=", "dead joint '' is not a joint (allowed 1..7"},
      {"sim?dead=2,x", "dead joint 'x'"},
      {"sim?swapped=8", "swapped joint '8' is not a joint (allowed 1..7"},
      {"unix:", "needs a socket path"},
      {"unix:/a?x=1", "takes no options"},
      {"serial:/dev/ttyAMA0", "needs select="},
      {"serial:ttyAMA0?select=1", "absolute device path"},
      {"serial:/dev/ttyAMA0?select=17,17", "given twice"},
      {"serial:/dev/ttyAMA0?select=1,2,3,4,5,6,7,8", "1..7 joints"},
      {"serial:/dev/ttyAMA0?select=a", "not a whole number"},
      {"serial:/dev/ttyAMA0?select=", "not a whole number"},
      {"serial:/dev/ttyAMA0?select=1&dialect=old", "neither standard nor legacy"},
      {"serial:/dev/ttyAMA0?select=1&baud=-1", "not a whole number"},
      {"serial:/dev/ttyAMA0?select=1&select=2", "given twice"},
      {"serial:/dev/ttyAMA0?select", "not key=value"},
  };
  for (const auto& [uri, why] : bad) {
    const auto r = parse_device_uri(uri);
    ASSERT_FALSE(r.ok()) << "accepted " << uri;
    const std::string& message = r.error().message;
    EXPECT_EQ(r.error().kind, ErrorKind::invalid_argument) << uri;
    EXPECT_NE(message.find(why), std::string::npos) << uri << ": " << message;
    EXPECT_NE(message.find("allowed:"), std::string::npos) << uri;
  }
}

}  // namespace
}  // namespace armctl::test

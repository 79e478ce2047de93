// Where the joint bus is: parsed and validated `--device` URIs.
//   sim                      an embedded simulated SCARA arm, in this process (default);
//                            optional ?baud=N&config=FILE&dead=J[,J...] (joints that never
//                            answer: to see how a dead joint is reported)&dialect=legacy
//                            (joints in legacy-master mode, answering the legacy dialect)
//                            &miscal=SEED (mis-assembled on purpose: core/miscalibration.hpp)
//                            &swapped=J[,J...] (motor leads swapped: driven, they run away)
//   unix:/path               a running `armctl sim scara --listen /path`
//   serial:/dev/ttyAMA0?baud=115200&chip=gpiochip0&select=17,27,22,5,6,13,19[&dialect=legacy]
//                            a real bus: UART + one GPIO line per joint (joints 1..N in
//                            the order given); baud defaults to 9600, chip to gpiochip0
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/error.hpp"
#include "devices/joint_bus/status_dialect.hpp"

namespace armctl::joint_bus {

struct SimDevice {
  std::optional<std::uint32_t> baud;  // empty: the config's baud
  std::string config;  // empty: config/scara.arm.json's simulator section
  std::vector<int> dead_joints;  // joints 1..7 whose controller never answers
  // Joints 1..7 whose motor leads are swapped: driven, each runs away and stops itself with
  // a runaway fault (to see a fault reported and cleared without hardware).
  std::vector<int> swapped_joints;
  Dialect dialect = Dialect::standard;  // legacy: every joint in legacy-master mode
  std::optional<std::uint32_t> miscal;  // the seed of a mis-assembly (core/miscalibration.hpp)
};

struct UnixDevice {
  std::string path;
};

struct SerialDevice {
  std::string path;
  std::uint32_t baud = 9600;
  std::string chip = "gpiochip0";
  std::vector<unsigned> select;  // GPIO line offset for joints 1..N
  Dialect dialect = Dialect::standard;
};

using DeviceUri = std::variant<SimDevice, UnixDevice, SerialDevice>;

// The device, or an error (invalid_argument) naming what was wrong and what is allowed.
Result<DeviceUri> parse_device_uri(std::string_view uri);

std::string describe(const DeviceUri& uri);  // for messages: "serial /dev/ttyAMA0 at 115200 baud"

}  // namespace armctl::joint_bus

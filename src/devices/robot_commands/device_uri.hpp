// Where a Robot Commands board is: `hid` (first xArm board), `hid:SERIAL`,
// `hid:/dev/hidrawN`, `serial:/dev/ttyUSB0[?baud=115200]`, a bare /dev path (serial), or
// `sim[?miscal=SEED]` (an emulated xArm embedded in the process: a simulator, so this SDK only
// parses it; devices::open_robot_commands in armctl_device_registry opens it; miscal: mis-
// assembled on purpose, core/miscalibration.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "devices/robot_commands/rc_link.hpp"

namespace armctl::robot_commands {

struct DeviceUri {
  enum class Kind { hid, serial, sim } kind = Kind::serial;
  std::string target;         // hid: serial number or hidraw path ("" = first); serial: path
  std::uint32_t baud = 9600;  // serial only
  std::optional<std::uint32_t> miscal;  // sim only: the seed of a mis-assembly
};

// Errors (invalid_argument) name what was wrong and list the accepted forms.
Result<DeviceUri> parse_device_uri(const std::string& text);

// Opens the link, or an error: io naming the device and why it cannot be opened,
// unsupported for sim.
Result<std::unique_ptr<RcLink>> open_link(const DeviceUri& uri);

}  // namespace armctl::robot_commands

// Opens what `armctl xarm --device URI` names (default `sim`: an emulated xArm embedded in
// this process, served on a pty and reached like a serial board) through the device registry.
#pragma once

#include <memory>
#include <string>

#include "devices/device_registry/device_registry.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::cli {

struct XarmSession {
  std::unique_ptr<devices::RcConnection> connection;
  std::unique_ptr<robot_commands::Client> client;
  ~XarmSession();
};

// Throws ArmctlError for a bad URI or a device that cannot be opened (the CLI prints it).
// `timeout_ms` 0 = the link's default reply timeout (1.5 s on HID, 500 ms otherwise). On
// HID, warnings found while opening go to stderr and the board must answer a first battery
// read.
std::unique_ptr<XarmSession> open_xarm_session(const std::string& device, int servo_count,
                                               int timeout_ms);

}  // namespace armctl::cli

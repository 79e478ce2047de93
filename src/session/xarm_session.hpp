// Opens what `armctl xarm --device URI` names (default `sim`: an emulated xArm embedded in
// this process, served on a pty and reached like a serial board) through the device registry.
#pragma once

#include <memory>
#include <string>

#include "devices/device_registry/device_registry.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::session {

struct XarmSession {
  std::unique_ptr<devices::RcConnection> connection;
  std::unique_ptr<robot_commands::Client> client;
  ~XarmSession();

  // Robot Commands cannot carry a refusal: a board ignores a frame it refuses (a save to a
  // read-only state dir, say) and at most logs why. For a request without a reply, with the
  // embedded board: waits until the board handled it (one battery read) and returns a device
  // error with what the board logged, if it refused. True when the outcome is known
  // (embedded board, accepted); false for a device that cannot confirm it.
  Result<bool> confirm_accepted(const std::string& what);
  // `status`, its error with what the embedded board logged added (e.g. why it sent no reply).
  Status check(Status status);
};

// The session, or the error for a bad URI or a device that cannot be opened.
// `timeout_ms` 0 = the link's default reply timeout (1.5 s on HID, 500 ms otherwise). On
// HID, warnings found while opening go to stderr and the board must answer a first battery
// read.
Result<std::unique_ptr<XarmSession>> open_xarm_session(const std::string& device, int servo_count,
                                                       int timeout_ms);

}  // namespace armctl::session

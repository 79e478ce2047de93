// The device registry: one place that turns a device URI into an open device, whatever it is:
// real hardware, a simulator in another process, or a simulator embedded in this process.
// The SDK libraries parse every URI form but link no simulator (DESIGN: "simulators are
// devices a user chooses by URI"); this library adds the embedded simulators on top, so an
// app, or the Arm API, opens `sim` exactly like `serial:/dev/ttyUSB0`.
//
//   joint bus:       sim[?baud=N&config=FILE&dead=J,...&miscal=SEED]  embedded simulated SCARA arm
//                    unix:/path, serial:/dev/...?select=... (joint_bus/device_uri.hpp)
//   Robot Commands:  sim[?miscal=SEED]                    embedded emulated xArm
//   miscal=SEED: mis-assembled on purpose (core/miscalibration.hpp); its truth goes to the debug
//   log only (core/debug_log.hpp), and a test reaches the physical arm with embedded_sim_arm /
//   embedded_xarm below.
//                    hid..., serial:/dev/...[?baud=N]     (robot_commands/device_uri.hpp)
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>
#include <string_view>

#include "core/error.hpp"
#include "devices/joint_bus/bus_connection.hpp"
#include "devices/joint_bus/device_uri.hpp"
#include "devices/robot_commands/device_uri.hpp"
#include "devices/robot_commands/rc_link.hpp"

namespace armctl::joint_sim {
class SimArm;
}
namespace armctl::xarm {
class EmulatorRunner;
}

namespace armctl::devices {

// The open device, or an error: invalid_argument for a bad URI (naming it and the accepted
// forms), io / invalid_config if the device or its config cannot be opened.
Result<std::unique_ptr<joint_bus::BusConnection>> open_joint_bus(std::string_view uri);
Result<std::unique_ptr<joint_bus::BusConnection>> open_joint_bus(const joint_bus::DeviceUri& uri);

// A Robot Commands device, open: its link, and whatever the link needs alive (an embedded
// emulated board serving a pty).
class RcConnection {
 public:
  virtual ~RcConnection() = default;
  virtual robot_commands::RcLink& link() = 0;
  // True for a board inside this process: it stops with the connection, so frames still
  // queued when a command ends are lost unless a request with a reply is sent first.
  virtual bool embedded() const = 0;
  // What an embedded board logged since the last call: refused frames and storage errors
  // (a read-only state dir). Robot Commands cannot carry a refusal (a board answers nothing),
  // so this is how a host in the same process learns why. Empty for any other device, which
  // keeps its log to itself.
  virtual std::vector<std::string> take_board_log() { return {}; }
};

// Same errors as open_joint_bus.
Result<std::unique_ptr<RcConnection>> open_robot_commands(std::string_view uri);
Result<std::unique_ptr<RcConnection>> open_robot_commands(const robot_commands::DeviceUri& uri);

// The simulator inside a connection opened from `sim...`, for tests that look at or move the
// physical arm (SimArm::true_position, move_by_hand_to; EmulatorRunner::with_servos); null for
// any other device. The xArm's board serves from its own thread: reach its servos only through
// with_servos.
joint_sim::SimArm* embedded_sim_arm(joint_bus::BusConnection& connection);
xarm::EmulatorRunner* embedded_xarm(RcConnection& connection);

// Where the embedded emulated xArm keeps what a real board keeps between power cycles (groups,
// saved offsets, servo limits): $ARMCTL_STATE_DIR/xarm-emulator, else
// $XDG_STATE_HOME/armctl/xarm-emulator, else ~/.local/state/armctl/xarm-emulator; an error
// (invalid_config) if none applies.
Result<std::filesystem::path> embedded_xarm_state_dir();

}  // namespace armctl::devices

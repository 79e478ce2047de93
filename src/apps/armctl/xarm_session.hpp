// Opens what `armctl xarm --device URI` names, or (without --device) an emulated xArm
// embedded in this process, served on a pty and reached like a serial board.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "devices/robot_commands/client.hpp"
#include "devices/xarm_emulator/emulator_runner.hpp"

namespace armctl::cli {

struct XarmSession {
  std::unique_ptr<xarm::EmulatorRunner> emulator;  // only without --device
  std::unique_ptr<robot_commands::RcLink> link;
  std::unique_ptr<robot_commands::Client> client;
  ~XarmSession();
};

// Where the embedded emulated xArm keeps its stored state (groups, saved offsets, servo
// limits): $ARMCTL_STATE_DIR/xarm-emulator, else $XDG_STATE_HOME/armctl/xarm-emulator, else
// ~/.local/state/armctl/xarm-emulator. Throws ArmctlError(invalid_config) if none applies.
std::filesystem::path embedded_state_dir();

// Throws ArmctlError for a bad URI or a device that cannot be opened.
std::unique_ptr<XarmSession> open_xarm_session(const std::string& device, int servo_count,
                                               int timeout_ms);

}  // namespace armctl::cli

// What the arm controller's earlier implementation (before it ran the portable core) kept in
// its state dir, brought into the core's group memory once: action groups
// (group-NNN.grp) and the joints' saved offsets and BusServoInfo limits
// (controller-settings.json). Sent through Robot Commands as a host would send them, so the
// core checks each as it checks any request. The old files are only read, never changed.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "devices/arm_controller/controller_config.hpp"
#include "devices/arm_controller/joint_settings.hpp"

namespace armctl::arm_controller {

class CoreDevice;

// What such a state dir holds, read before the core's memory is created.
struct DaemonState {
  std::filesystem::path dir;
  ControllerSettings settings;  // the defaults if it had no settings file
};

// The earlier implementation's state in `state_dir`, if it has either kind of file: its
// settings read now, so that a file it cannot read stops the start with the reason before
// anything is created (throws ArmctlError: invalid_config, io; a corrupt file is never
// taken as the defaults). Nothing there: nullopt.
std::optional<DaemonState> find_daemon_state(const std::filesystem::path& state_dir, const ControllerConfig& config);

// Imports `state` into `device` (just started, its group memory new); returns the log lines:
// what was imported, and each group or setting that could not be (the reason), e.g. a group
// whose positions the arm file's soft limits no longer allow.
std::vector<std::string> import_daemon_state(const DaemonState& state, const ControllerConfig& config,
                                             CoreDevice& device);

}  // namespace armctl::arm_controller

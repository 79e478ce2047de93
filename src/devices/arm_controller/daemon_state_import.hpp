// What the arm controller's earlier implementation (before it ran the portable core) kept in
// its state dir, brought into the core's group memory once: action groups
// (group-NNN.grp) and the joints' saved offsets and BusServoInfo limits
// (controller-settings.json). Sent through Robot Commands as a host would send them, so the
// core checks each as it checks any request. The old files are only read, never changed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "devices/arm_controller/controller_config.hpp"

namespace armctl::arm_controller {

class CoreDevice;

// True if `state_dir` holds either kind of file.
bool has_daemon_state(const std::filesystem::path& state_dir);

// Throws ArmctlError (invalid_config, io) if its settings file cannot be read, naming what is
// wrong: a corrupt file is never taken as the defaults.
void check_daemon_state(const std::filesystem::path& state_dir, const ControllerConfig& config);

// Imports into `device` (just started, its group memory new); returns the log lines: what
// was imported, and each group or setting that could not be (the reason), e.g. a group
// whose positions the arm file's soft limits no longer allow.
std::vector<std::string> import_daemon_state(const std::filesystem::path& state_dir, const ControllerConfig& config,
                                             CoreDevice& device);

}  // namespace armctl::arm_controller

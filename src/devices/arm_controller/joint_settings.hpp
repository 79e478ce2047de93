// What the arm controller's earlier implementation kept per joint across restarts: the
// saved zero offset (ServoOffsetWrite) and the limits set with BusServoInfoWrite, plus which
// joint BusServoInfoRead/Write address, as <state dir>/controller-settings.json. The
// controller now keeps them in the core's group memory (core_device.hpp); this file is read
// once, by the import of such a state dir (daemon_state_import.hpp). A corrupt file is an
// error naming what is wrong, never silently replaced by defaults. (save_settings writes
// the format: tests and the fuzz target make files with it.)
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string_view>

#include "core/error.hpp"
#include "devices/rc_board/arm_backend.hpp"

namespace armctl::arm_controller {

struct JointSettings {
  std::int8_t saved_offset = 0;
  rc_board::BusServoLimits limits;  // limits.servo = the joint's number
  bool operator==(const JointSettings&) const = default;
};

struct ControllerSettings {
  std::map<int, JointSettings> joints;  // by joint number
  int info_joint = 1;
  bool operator==(const ControllerSettings&) const = default;
};

std::filesystem::path settings_path(const std::filesystem::path& state_dir);
// The file is outside input (hand-edited, truncated, from another arm config), so it is read
// strictly: exactly the keys save_settings writes, joint keys exactly the decimal number of a
// joint in `defaults` (the arm config), integers only, each in the range the controller
// itself accepts (ServoOffsetAdjust -125..125, BusServoInfoWrite limits). Joints of the config
// missing from the file keep their defaults. Any problem: invalid_config naming `source`, the
// key and what is allowed; nothing of the file is applied.
Result<ControllerSettings> parse_settings(std::string_view text, std::string_view source,
                                          const ControllerSettings& defaults);
// Nothing stored yet: `defaults`. Errors: io, invalid_config (as parse_settings).
Result<ControllerSettings> load_settings(const std::filesystem::path& state_dir,
                                         const ControllerSettings& defaults);
Status save_settings(const std::filesystem::path& state_dir, const ControllerSettings& settings);

}  // namespace armctl::arm_controller

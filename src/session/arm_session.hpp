// Opens what `armctl arm --arm A --device URI` (and Python's `armctl.Arm(arm, device)`)
// names: the arm model (shipped xarm/scara or an arm file) and a device for it, by the URI's
// kind (session/device_kinds.hpp). Without --device: `sim`, the xArm on an emulated xArm
// board embedded in this process, the SCARA on an embedded simulated arm on the joint bus.
// For the SCARA, joint-bus URIs (sim..., unix:..., serial:...&select=...) drive the joints
// directly; any Robot Commands URI (hid, serial:..., /dev/...) drives it through armctl's
// arm controller.
#pragma once

#include <memory>
#include <string>

#include "arm/arm.hpp"
#include "session/device_kinds.hpp"

namespace armctl::session {

struct ArmSession {
  // Destroyed in reverse: the arm first, then what its device talks through.
  std::shared_ptr<void> connection;
  std::unique_ptr<arm::Arm> arm;
  bool reconnects = false;  // OpenedDevice::reconnects
  bool paced = false;       // OpenedDevice::paced
  robot_commands::Client* board = nullptr;  // OpenedDevice::board
};

// A URI that names a joint bus (sim..., unix:..., serial:...&select=...), not a Robot
// Commands board (session/builtin_device_kinds.cpp, which opens them).
bool device_is_joint_bus(const std::string& device);

// The arm model `arm` names (shipped xarm/scara or an arm file), or the error naming what
// was wrong with it.
Result<arm::ArmModel> load_arm(const std::string& arm);

// The arm and its device, or the error naming what was wrong (arm file, URI, device).
Result<std::unique_ptr<ArmSession>> open_arm_session(const std::string& arm, const std::string& device,
                                                     const SessionOptions& options = {});

}  // namespace armctl::session

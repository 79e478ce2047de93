// Opens what `armctl arm --arm A --device URI` (and Python's `armctl.Arm(arm, device)`)
// names: the arm model (shipped xarm/scara or an arm file) and a device for it. Without
// --device: the xArm on an emulated xArm board embedded in this process, the SCARA on an
// embedded simulated arm on the joint bus.
// For the SCARA, joint-bus URIs (sim..., unix:..., serial:...&select=...) drive the joints
// directly; any Robot Commands URI (hid, serial:..., /dev/...) drives it through armctl's
// arm controller.
#pragma once

#include <memory>
#include <string>

#include "session/xarm_session.hpp"
#include "arm/arm.hpp"
#include "devices/joint_bus/bus_connection.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_bus/reconnecting_link.hpp"

namespace armctl::session {

struct ArmSession {
  // Destroyed in reverse: the arm first, then what it talks through.
  std::unique_ptr<XarmSession> rc;
  std::unique_ptr<joint_bus::BusConnection> bus;
  std::unique_ptr<transport::JointBusLink> paced;  // the embedded sim in step with the wall clock
  std::unique_ptr<joint_bus::ReconnectingLink> reconnecting;  // SessionOptions::reconnect
  std::unique_ptr<joint_bus::BusMaster> master;
  std::unique_ptr<arm::Arm> arm;
};

// A URI that names a joint bus (sim..., unix:..., serial:...&select=...), not a Robot
// Commands board.
bool device_is_joint_bus(const std::string& device);

// The arm model `arm` names (shipped xarm/scara or an arm file), or the error naming what
// was wrong with it.
Result<arm::ArmModel> load_arm(const std::string& arm);

struct SessionOptions {
  // The embedded simulated joint bus runs on simulated time, as fast as the host goes (what
  // the CLI and tests want). Servers that many clients watch live (the ROS node, the web
  // dashboard) want it in step with the wall clock instead, like a real arm.
  bool wall_clock = false;
  // A joint-bus link that closes (`armctl sim scara --listen` restarted, a USB-serial adapter
  // pulled out) is opened again with back-off, under the same arm: what a server that runs
  // for days wants. Each call meanwhile fails with the loss ("the joint bus link is lost
  // ...; reconnecting"). Robot Commands devices are not reopened (docs/http-api.md).
  bool reconnect = false;
};
// The arm and its device, or the error naming what was wrong (arm file, URI, device).
Result<std::unique_ptr<ArmSession>> open_arm_session(const std::string& arm, const std::string& device,
                                                     const SessionOptions& options = {});

}  // namespace armctl::session

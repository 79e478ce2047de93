// The JSON of GET /api/v1/model and /api/v1/state (and each SSE event): built from the
// arm model and the worker's snapshot only, never from the device. Units as people read
// them: deg or mm (velocities per s), the tool in mm and deg.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "arm/arm.hpp"
#include "session/arm_worker.hpp"
#include "web/control_lease.hpp"
#include "web/program_run.hpp"

namespace armctl::web {

using json = nlohmann::json;

// What the server knows of its device from the start.
struct DeviceInfo {
  std::string device;       // the URI as given ("" = the embedded simulator)
  std::string description;  // the device's own description
  arm::Protocol protocol = arm::Protocol::robot_commands;
  bool groups_supported = false;  // the device has action groups (a Robot Commands board)
  // A lost link is opened again by itself (a joint bus on a socket or serial port, and the
  // embedded simulators, which cannot be lost); else `serve` must be restarted.
  bool reconnects = false;
};

// Of an open session (before it is handed to the worker): `uri` as the user gave it.
DeviceInfo describe_device(session::ArmSession& session, const std::string& uri);

json model_json(const arm::ArmModel& model, const DeviceInfo& device);

// `arm` for its model-only calls (tool_rpy); nothing is read from the device.
json state_json(const arm::ArmKinematics& arm, const DeviceInfo& device, const session::ArmSnapshot& snapshot,
                const ControlView& control, const std::optional<ProgramView>& program);

// The tool pose as {"x","y","z" (mm), "roll","pitch","yaw" (deg)}.
json tool_json(const arm::ArmKinematics& arm, const motion::Pose& pose, const std::vector<double>& positions);

}  // namespace armctl::web

// The kinds of device an arm can be opened on, by the kind of its URI (`sim`, `unix:`,
// `serial:`, `hid`, or one added with register_device_kind): each kind's factory opens the
// device for an arm model and hands back an arm::ArmDevice with whatever it talks through.
// An open table (core/named_registry.hpp): a new transport is one folder with its device and
// one registration, and no app changes (docs/architecture.md "How to add a device").
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "arm/arm_device.hpp"
#include "arm/arm_model.hpp"
#include "core/error.hpp"
#include "devices/robot_commands/client.hpp"
#include "transport/device_uri_parts.hpp"

namespace armctl::session {

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
  // A scene file (docs/scene.md) every plan of the arm is checked against, read before the
  // device is opened (a bad file opens nothing). Empty: self-collision only.
  std::filesystem::path scene{};
  // The scene's fence and reduced mode switched on or off from the start (empty: as the
  // file says); switching one the scene does not set is refused before anything opens.
  std::optional<bool> fence{}, reduced_mode{};
};

// What a factory is asked to open.
struct DeviceRequest {
  const arm::ArmModel& model;
  std::string uri;           // as given; "sim" when none was
  transport::UriParts parts;  // the URI split (transport::split_uri)
  SessionOptions options;
};

// An open device and what it talks through (a board's client, a bus and its master),
// destroyed after the device.
struct OpenedDevice {
  std::shared_ptr<void> connection;
  std::unique_ptr<arm::ArmDevice> device;
  // A lost link is opened again by itself (SessionOptions::reconnect, where the kind can).
  bool reconnects = false;
  bool paced = false;  // an embedded simulator held in step with the wall clock
  // A Robot Commands board's client (owned by `connection`), for what lies under the arm:
  // its servos' IDs and offsets (the calibration wizard); nullptr for other devices.
  robot_commands::Client* board = nullptr;
};

// May throw (a device's constructor): open_arm_session turns that into its error.
using DeviceFactory = std::function<Result<OpenedDevice>(const DeviceRequest&)>;

// Adds a URI kind (invalid_argument if it is taken). The built-in ones (sim, unix, serial,
// hid) are there from the start.
Status register_device_kind(std::string kind, DeviceFactory open);
// The factory for `kind`, or invalid_argument "unknown device kind 'x' (known: ...)".
Result<const DeviceFactory*> find_device_kind(std::string_view kind);

}  // namespace armctl::session

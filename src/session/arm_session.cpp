#include "session/arm_session.hpp"

#include <thread>
#include <utility>

#include <fmt/core.h>

#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "devices/device_registry/device_registry.hpp"
#include "transport/device_uri_parts.hpp"
#include "transport/paced_link.hpp"

namespace armctl::session {

// Read with the one URI parser, so the forms are those of docs/joint-bus-master.md.
bool device_is_joint_bus(const std::string& device) {
  const auto parts = transport::split_uri(device);
  if (!parts) return false;  // the Robot Commands parser names the mistake
  return parts->kind == "sim" || parts->kind == "unix" ||
         (parts->kind == "serial" && parts->options.contains("select"));
}

Result<arm::ArmModel> load_arm(const std::string& arm) { return arm::load_arm_model(arm::arm_file_path(arm)); }

namespace {

// The device for `model`; may throw (the reconnecting link's first open, a device's
// constructor): open_arm_session turns that into its error.
Result<std::unique_ptr<ArmSession>> open_device(arm::ArmModel model, const std::string& device,
                                                const SessionOptions& options) {
  auto s = std::make_unique<ArmSession>();
  const bool bus = model.supports(arm::Protocol::joint_bus) &&
                   (device.empty() || device_is_joint_bus(device) || !model.supports(arm::Protocol::robot_commands));
  if (bus) {
    auto opened = devices::open_joint_bus(device.empty() ? "sim" : device);
    if (!opened) return opened.error();
    s->bus = std::move(opened).value();
    transport::JointBusLink* link = &s->bus->link();
    if (options.wall_clock && transport::runs_on_simulated_time(*link)) {
      s->paced = std::make_unique<transport::PacedLink>(*link);
      link = s->paced.get();
    } else if (options.reconnect && !transport::runs_on_simulated_time(*link)) {
      // The first link is the one just opened (kept by s->bus); later ones are opened anew.
      auto open = [uri = device, first = link]() mutable -> std::shared_ptr<transport::JointBusLink> {
        if (first) return std::shared_ptr<transport::JointBusLink>(std::exchange(first, nullptr), [](auto*) {});
        std::shared_ptr<joint_bus::BusConnection> c(devices::open_joint_bus(uri).value());
        return std::shared_ptr<transport::JointBusLink>(c, &c->link());  // lives as long as its connection
      };
      joint_bus::ReconnectOptions reconnect;
      reconnect.while_lost = joint_bus::ReconnectOptions::WhileLost::refuse;
      s->reconnecting = std::make_unique<joint_bus::ReconnectingLink>(
          std::move(open), link->clock(), [](TimePoint t) { std::this_thread::sleep_until(t); }, nullptr, reconnect);
      link = s->reconnecting.get();
    }
    s->master = std::make_unique<joint_bus::BusMaster>(*link, s->bus->default_options());
    auto dev = std::make_unique<arm::BusArmDevice>(model, *s->master, *link, s->bus->description());
    s->arm = std::make_unique<arm::Arm>(std::move(model), std::move(dev));
  } else {
    int servos = 0;
    for (const auto& j : model.joints) servos = std::max(servos, j.robot_commands->id);
    auto rc = open_xarm_session(device, servos, 0);  // 0: the link's reply timeout (HID: 1.5 s)
    if (!rc) return rc.error();
    s->rc = std::move(rc).value();
    auto dev = std::make_unique<arm::RcArmDevice>(model, *s->rc->client);
    s->arm = std::make_unique<arm::Arm>(std::move(model), std::move(dev));
  }
  return s;
}

}  // namespace

Result<std::unique_ptr<ArmSession>> open_arm_session(const std::string& arm_name, const std::string& device,
                                                     const SessionOptions& options) {
  auto model = load_arm(arm_name);
  if (!model) return model.error();
  return catch_error([&] { return open_device(std::move(model).value(), device, options); });
}

}  // namespace armctl::session

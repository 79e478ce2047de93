// The built-in device kinds, registered here and nowhere else: the URI kinds of the joint bus
// (sim, unix:, serial:...&select=) and of Robot Commands boards (sim, hid, serial:), each
// opened through the device registry (devices/device_registry), simulators included.
#include <algorithm>
#include <thread>
#include <utility>

#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "core/named_registry.hpp"
#include "devices/device_registry/device_registry.hpp"
#include "devices/joint_bus/bus_connection.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_bus/reconnecting_link.hpp"
#include "session/arm_session.hpp"
#include "session/device_kinds.hpp"
#include "session/xarm_session.hpp"
#include "transport/paced_link.hpp"

namespace armctl::session {

namespace {

// What a joint-bus arm talks through; destroyed in reverse: the master first.
struct BusStack {
  std::unique_ptr<joint_bus::BusConnection> bus;
  std::unique_ptr<transport::JointBusLink> paced;  // the embedded sim in step with the wall clock
  std::unique_ptr<joint_bus::ReconnectingLink> reconnecting;  // SessionOptions::reconnect
  std::unique_ptr<joint_bus::BusMaster> master;
};

Result<OpenedDevice> open_bus_arm(const DeviceRequest& r) {
  auto stack = std::make_shared<BusStack>();
  auto opened = devices::open_joint_bus(r.uri);
  if (!opened) return opened.error();
  stack->bus = std::move(opened).value();
  transport::JointBusLink* link = &stack->bus->link();
  const bool simulated = transport::runs_on_simulated_time(*link);
  if (r.options.wall_clock && simulated) {
    stack->paced = std::make_unique<transport::PacedLink>(*link);
    link = stack->paced.get();
  } else if (r.options.reconnect && !simulated) {
    // The first link is the one just opened (kept by stack->bus); later ones are opened anew.
    auto open = [uri = r.uri, first = link]() mutable -> std::shared_ptr<transport::JointBusLink> {
      if (first) return std::shared_ptr<transport::JointBusLink>(std::exchange(first, nullptr), [](auto*) {});
      std::shared_ptr<joint_bus::BusConnection> c(devices::open_joint_bus(uri).value());
      return std::shared_ptr<transport::JointBusLink>(c, &c->link());  // lives as long as its connection
    };
    joint_bus::ReconnectOptions reconnect;
    reconnect.while_lost = joint_bus::ReconnectOptions::WhileLost::refuse;
    stack->reconnecting = std::make_unique<joint_bus::ReconnectingLink>(
        std::move(open), link->clock(), [](TimePoint t) { std::this_thread::sleep_until(t); }, nullptr, reconnect);
    link = stack->reconnecting.get();
  }
  stack->master = std::make_unique<joint_bus::BusMaster>(*link, stack->bus->default_options());
  OpenedDevice out;
  out.device = std::make_unique<arm::BusArmDevice>(r.model, *stack->master, *link, stack->bus->description());
  out.reconnects = stack->reconnecting != nullptr;
  out.paced = stack->paced != nullptr;
  out.connection = std::move(stack);
  return out;
}

Result<OpenedDevice> open_rc_arm(const DeviceRequest& r) {
  int servos = 0;
  for (const auto& j : r.model.joints)
    if (const arm::DeviceMap* m = j.map(arm::Protocol::robot_commands)) servos = std::max(servos, m->id);
  auto rc = open_xarm_session(r.uri, servos, 0);  // 0: the link's reply timeout (HID: 1.5 s)
  if (!rc) return rc.error();
  std::shared_ptr<XarmSession> board = std::move(rc).value();
  OpenedDevice out;
  out.device = std::make_unique<arm::RcArmDevice>(r.model, *board->client);
  out.board = board->client.get();
  out.connection = std::move(board);
  return out;
}

// The forms of docs/joint-bus-master.md: sim, unix:, and serial: with its select lines.
bool names_joint_bus(const transport::UriParts& parts) {
  return parts.kind == "sim" || parts.kind == "unix" || (parts.kind == "serial" && parts.options.contains("select"));
}

// Every built-in kind is named by both protocols' URIs (`sim` is the emulated xArm board or
// the simulated SCARA arm; `serial:` a board or a bus): the joint bus when the URI names one
// or the arm has no Robot Commands mapping, else the board. Each protocol's own opener names
// any mistake in the URI.
Result<OpenedDevice> open_builtin(const DeviceRequest& r) {
  const bool bus = r.model.supports(arm::Protocol::joint_bus) &&
                   (names_joint_bus(r.parts) || !r.model.supports(arm::Protocol::robot_commands));
  return bus ? open_bus_arm(r) : open_rc_arm(r);
}

}  // namespace

bool device_is_joint_bus(const std::string& device) {
  const auto parts = transport::split_uri(device);
  return parts && names_joint_bus(*parts);  // a bad URI: the Robot Commands parser names the mistake
}

void add_builtin_device_kinds(NamedRegistry<DeviceFactory>& table) {
  // A fresh table: a clash is a bug here, thrown.
  for (const char* kind : {"sim", "unix", "serial", "hid"}) table.add(kind, open_builtin).value();
}

}  // namespace armctl::session

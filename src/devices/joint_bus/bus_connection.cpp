#include "devices/joint_bus/bus_connection.hpp"

#include <chrono>

#include <fmt/core.h>

#include "devices/joint_bus/sim_link_client.hpp"
#include "core/error.hpp"
#include "transport/gpiod_select_lines.hpp"
#include "transport/serial_joint_bus_link.hpp"
#include "transport/serial_port.hpp"

namespace armctl::joint_bus {

namespace {

class RemoteSim final : public BusConnection {
 public:
  explicit RemoteSim(const UnixDevice& d) : path_(d.path), client_(d.path) {}
  transport::JointBusLink& link() override { return client_; }
  MasterOptions default_options() const override {
    MasterOptions o;
    // The arm runs paced to the wall clock in another process: a turnaround covers the
    // socket round trip and the arm's 1 ms pacing steps, with room for a loaded machine
    // (either process may be descheduled for tens of milliseconds).
    o.timing.turnaround = std::chrono::milliseconds(200);
    return o;
  }
  std::string description() const override { return fmt::format("simulated arm at {}", path_); }

 private:
  std::string path_;
  SimLinkClient client_;
};

class RealBus final : public BusConnection {
 public:
  explicit RealBus(const SerialDevice& d) : device_(d) {
    auto select = transport::GpiodSelectLines::open(d.chip, d.select);
    auto port = transport::SerialPort::open(d.path, d.baud);
    link_ = std::make_unique<transport::SerialJointBusLink>(std::move(port), std::move(select), d.baud);
  }
  transport::JointBusLink& link() override { return *link_; }
  MasterOptions default_options() const override {
    MasterOptions o;
    o.dialect = device_.dialect;
    // Linux scheduling and USB/UART FIFOs add latency a microcontroller master would not see.
    o.timing.turnaround = std::chrono::milliseconds(20);
    return o;
  }
  std::string description() const override { return describe(DeviceUri{device_}); }

 private:
  SerialDevice device_;
  std::unique_ptr<transport::SerialJointBusLink> link_;
};

}  // namespace

Result<std::unique_ptr<BusConnection>> open_bus(const DeviceUri& uri) {
  if (std::holds_alternative<SimDevice>(uri)) {
    return Error{ErrorKind::unsupported,
                 "device \"sim\" (the embedded simulated arm) is a simulator: open it with "
                 "devices::open_joint_bus (library armctl_device_registry)"};
  }
  // The connections' constructors open ports and sockets and throw; this is the boundary.
  return catch_error([&]() -> Result<std::unique_ptr<BusConnection>> {
    if (const auto* u = std::get_if<UnixDevice>(&uri)) return {std::make_unique<RemoteSim>(*u)};
    return {std::make_unique<RealBus>(std::get<SerialDevice>(uri))};
  });
}

void idle(transport::JointBusLink& link, Duration d) {
  const TimePoint until = link.clock().now() + d;
  while (link.read_byte(until)) {
  }
}

}  // namespace armctl::joint_bus

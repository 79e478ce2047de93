// Opens the joint bus a DeviceUri names: the link the master talks through, whatever owns
// it (a serial port and GPIO lines, a socket to a simulated arm in another process), and the
// master options that suit that link (dialect; a turnaround that covers a socket round trip).
// This library links no simulator: the embedded simulated arm (`sim`) is opened by the device
// registry (devices/device_registry), which apps use to open any URI.
#pragma once

#include <memory>
#include <string>

#include "core/error.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_bus/device_uri.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::joint_bus {

class BusConnection {
 public:
  virtual ~BusConnection() = default;
  virtual transport::JointBusLink& link() = 0;
  virtual MasterOptions default_options() const = 0;
  virtual std::string description() const = 0;
};

// The connection, or an error (io, invalid_config, invalid_argument) naming what failed;
// unsupported for SimDevice.
Result<std::unique_ptr<BusConnection>> open_bus(const DeviceUri& uri);

// Lets time pass on the link's clock without a transaction (simulated links advance the
// arm; real links wait). Bytes that arrive meanwhile are stray and discarded.
void idle(transport::JointBusLink& link, Duration d);

}  // namespace armctl::joint_bus

// What the portable arm-controller core (portable_controller/controller_core.hpp) needs of
// its board, on Linux: the joint bus through a transport::JointBusLink, and its group
// memory as a file (or RAM). The Mega firmware has its own (firmware/mega/).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "devices/arm_controller/controller_config.hpp"
#include "portable_controller/bus_master.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/group_store.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::arm_controller {

// The core's bus port over a JointBusLink. Lowering select first waits for every queued
// byte to leave the wire (flush), as the port contract asks.
class LinkBusPort final : public controller::BusPort {
 public:
  explicit LinkBusPort(transport::JointBusLink& link) : link_(link) {}
  void set_select(std::uint8_t joint, bool high) override;
  void send_byte(std::uint8_t byte) override;

 private:
  transport::JointBusLink& link_;
};

// The core's group memory (action groups and the servo settings record) as a file of
// `size` bytes: read whole when opened (a missing file is a blank memory, 0xFF, as an
// erased EEPROM), every byte write written through at once (pwrite). The core's store
// never half-stores a group across a reset after any single byte write, so a killed
// process loses nothing it acknowledged. Without a path: RAM only.
class FileGroupMemory final : public controller::GroupMemory {
 public:
  // Throws ArmctlError(io) if the file cannot be opened or created, or
  // (invalid_config) if it exists with another size (not a memory this wrote).
  FileGroupMemory(std::optional<std::filesystem::path> path, std::uint32_t size);
  ~FileGroupMemory();
  FileGroupMemory(const FileGroupMemory&) = delete;
  FileGroupMemory& operator=(const FileGroupMemory&) = delete;

  std::uint32_t size() const override { return static_cast<std::uint32_t>(bytes_.size()); }
  std::uint8_t read(std::uint32_t address) override { return bytes_[address]; }
  bool ready() override { return true; }
  // Throws ArmctlError(io) if the file write fails (a full disk): the core must not take a
  // byte as stored that is not.
  void write(std::uint32_t address, std::uint8_t value) override;

 private:
  std::vector<std::uint8_t> bytes_;
  int fd_ = -1;
};

// The core's joints from the arm file's arm_controller section: its map's values at
// positions 0 and 1000, soft limits, speed, acceleration and zone. Throws
// ArmctlError(invalid_config) naming the joint and value that the core cannot hold
// (clicks beyond -32768..32767, a speed beyond 65535, more than 7 joints; the arm file's
// own ranges keep within them).
std::vector<controller::JointSetup> core_joint_setups(const ControllerConfig& config);

}  // namespace armctl::arm_controller

// Robot Commands over USB HID: one frame per 64-byte report (report ID 0x00 on writes; reads
// accepted with or without a leading 0x00; padding stripped using LEN). The report framing
// is pure code in protocol/robot_commands/hid_report.hpp and tested there; this class has
// NOT been verified against a real board here (no hardware): see docs/robot-commands.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "devices/robot_commands/rc_link.hpp"
#include "transport/hid_device.hpp"

namespace armctl::robot_commands {

constexpr std::uint16_t kXarmVendorId = 0x0483;
constexpr std::uint16_t kXarmProductId = 0x5750;
constexpr const char* kXarmProduct = "LOBOT";

// xArm boards attached: 0483:5750 with product string "LOBOT" (other 0483:5750 devices,
// e.g. other STM32 HID gadgets, are left out).
std::vector<transport::HidDeviceInfo> find_xarm_boards();

class HidLink final : public RcLink {
 public:
  // Opens by hidraw path. Throws ArmctlError(io).
  explicit HidLink(const std::string& path, std::string serial_number = {});
  // "" = the first board; otherwise the board with this serial number or hidraw path.
  // Throws ArmctlError(io) listing what was found if there is no match.
  static std::unique_ptr<HidLink> open_board(const std::string& serial_or_path);

  void send(const rc::Frame& frame) override;
  std::optional<rc::Frame> receive(TimePoint deadline) override;
  const Clock& clock() const override { return device_.clock(); }
  std::string describe() const override;
  std::size_t discarded() const override { return discarded_; }

 private:
  transport::HidDevice device_;
  std::string serial_;
  std::size_t discarded_ = 0;
};

}  // namespace armctl::robot_commands

// Robot Commands over USB HID: one frame per 64-byte report (report ID 0x00 on writes; reads
// accepted with or without a leading 0x00; padding stripped using LEN). The report framing
// is pure code in protocol/robot_commands/hid_report.hpp and tested there. The timings
// below follow what drivers that work with real boards learned; this code has NOT been run
// against a real board here (no hardware): see docs/usb-hid.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "devices/robot_commands/client.hpp"
#include "devices/robot_commands/rc_link.hpp"
#include "transport/hid_device.hpp"

namespace armctl::robot_commands {

constexpr std::uint16_t kXarmVendorId = 0x0483;
constexpr std::uint16_t kXarmProductId = 0x5750;
constexpr const char* kXarmProduct = "LOBOT";

// Client options for an xArm board on HID (docs/usb-hid.md says why each value):
// replies wait 1.5 s (real boards take up to ~450 ms for a position read), reads are sent
// up to 3 times, `watch` polls every 500 ms, servo-off goes one frame per servo.
ClientOptions hid_client_options(int servo_count = 6);

// xArm boards attached: 0483:5750 with product string "LOBOT" (other 0483:5750 devices,
// e.g. other STM32 HID gadgets, are left out).
std::vector<transport::HidDeviceInfo> find_xarm_boards(
    transport::HidBackend& backend = transport::hidapi_backend());

class HidLink final : public RcLink {
 public:
  explicit HidLink(std::unique_ptr<transport::HidPort> port, std::string serial_number = {});
  // "" = the first board; a /dev path = that node, even if it is not listed as an xArm
  // board (clones with another product string exist; a warning says so); otherwise the
  // board with this serial number. Throws ArmctlError(io) listing what was found if there
  // is no match, or if the device cannot be opened (e.g. another program holds it).
  static std::unique_ptr<HidLink> open_board(
      const std::string& serial_or_path,
      transport::HidBackend& backend = transport::hidapi_backend());

  void send(const rc::Frame& frame) override;
  std::optional<rc::Frame> receive(TimePoint deadline) override;
  const Clock& clock() const override { return port_->clock(); }
  // Names the programs that also have the node open, if any: their replies reach us too.
  std::string describe() const override;
  std::size_t discarded() const override { return discarded_; }
  // One 64-byte report per USB frame (1 ms, full speed), and the board then forwards each
  // servo's command on its servo bus: 10 bytes per servo at 115200 baud. A frame of
  // `serial_bytes` bytes moving n = (bytes - 7) / 3 servos is paced by the slower of the two.
  Duration frame_time(std::size_t serial_bytes) const override;

  // Things a user should know about this board, found while opening (not an xArm product
  // string, other programs with the node open). The CLI prints them as warnings.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  std::unique_ptr<transport::HidPort> port_;
  std::string serial_;
  std::size_t discarded_ = 0;
  std::vector<std::string> warnings_;
};

// Right after opening, a real board can need a second or two before it answers (one
// driver retries a battery read five times, 1 s apart). Reads the battery voltage under
// the client's read retries; the error says what to check when the board never answers.
Status await_first_contact(Client& client);

}  // namespace armctl::robot_commands

// USB HID devices through hidapi (hidraw backend): enumerate by vendor/product, open by
// path, write/read raw reports. Robot Commands framing inside reports lives in
// protocol/robot_commands/hid_report.hpp; this layer only moves bytes.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/clock.hpp"

struct hid_device_;

namespace armctl::transport {

struct HidDeviceInfo {
  std::string path;           // /dev/hidrawN
  std::string serial_number;  // may be empty
  std::string manufacturer;
  std::string product;        // "LOBOT" on xArm boards
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  int interface_number = -1;
};

// Every HID device with this vendor/product (0 = any). Throws ArmctlError(io) if hidapi
// cannot start.
std::vector<HidDeviceInfo> hid_enumerate(std::uint16_t vendor_id, std::uint16_t product_id);

class HidDevice {
 public:
  // Throws ArmctlError(io) naming the path (and a udev hint on permission problems).
  explicit HidDevice(const std::string& path);
  ~HidDevice();
  HidDevice(const HidDevice&) = delete;
  HidDevice& operator=(const HidDevice&) = delete;

  // The whole buffer is one output report, report ID first. Throws ArmctlError(io).
  void write(std::span<const std::uint8_t> report);
  // One input report into `buffer`, waiting until `deadline` (steady clock); 0 = timed out.
  std::size_t read(std::span<std::uint8_t> buffer, TimePoint deadline);
  const std::string& path() const { return path_; }
  const Clock& clock() const { return clock_; }

 private:
  hid_device_* dev_ = nullptr;
  std::string path_;
  SteadyClock clock_;
};

}  // namespace armctl::transport

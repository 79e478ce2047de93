// USB HID devices: enumerate by vendor/product, open by path, write/read raw reports.
// Robot Commands framing inside reports lives in protocol/robot_commands/hid_report.hpp;
// this layer only moves bytes.
//
// The seam: HidBackend (enumerate + open) and HidPort (one open device). The real ones go
// through hidapi's hidraw backend (hidapi_backend(), HidDevice); tests put a fake board
// under the same seam, on simulated time.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "transport/hid_device_lock.hpp"

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

// One open HID device.
class HidPort {
 public:
  virtual ~HidPort() = default;
  // The whole buffer is one output report, report ID first. Throws ArmctlError(io).
  virtual void write(std::span<const std::uint8_t> report) = 0;
  // One input report into `buffer`, waiting until `deadline` (on clock()); 0 = timed out.
  // Throws ArmctlError(io).
  virtual std::size_t read(std::span<std::uint8_t> buffer, TimePoint deadline) = 0;
  virtual const std::string& path() const = 0;
  virtual const Clock& clock() const = 0;
  // Other programs that have this device open, for messages ("fwupd (pid 812)"); "" if
  // none or unknown. Their requests' replies reach every handle.
  virtual std::string other_users() const { return {}; }
};

class HidBackend {
 public:
  virtual ~HidBackend() = default;
  // Every HID device with this vendor/product (0 = any). Throws ArmctlError(io).
  virtual std::vector<HidDeviceInfo> enumerate(std::uint16_t vendor_id,
                                               std::uint16_t product_id) = 0;
  // Throws ArmctlError(io) naming the path (and a udev hint on permission problems, or
  // the program holding the device).
  virtual std::unique_ptr<HidPort> open(const std::string& path) = 0;
};

// hidapi (hidraw). Lives for the whole process.
HidBackend& hidapi_backend();

// Every HID device with this vendor/product (0 = any), through hidapi. Throws
// ArmctlError(io) if hidapi cannot start.
std::vector<HidDeviceInfo> hid_enumerate(std::uint16_t vendor_id, std::uint16_t product_id);

// A device opened through hidapi, with an advisory exclusive lock on its node (see
// hid_device_lock.hpp): a second armctl is refused with the holder's name.
class HidDevice final : public HidPort {
 public:
  // Throws ArmctlError(io) naming the path (and a udev hint on permission problems).
  explicit HidDevice(const std::string& path);
  ~HidDevice() override;
  HidDevice(const HidDevice&) = delete;
  HidDevice& operator=(const HidDevice&) = delete;

  void write(std::span<const std::uint8_t> report) override;
  std::size_t read(std::span<std::uint8_t> buffer, TimePoint deadline) override;
  const std::string& path() const override { return path_; }
  const Clock& clock() const override { return clock_; }
  std::string other_users() const override { return holders_text(programs_holding(path_)); }

 private:
  std::string path_;
  NodeLock lock_;  // taken before hidapi opens the node, dropped after it closes it
  hid_device_* dev_ = nullptr;
  SteadyClock clock_;
};

}  // namespace armctl::transport

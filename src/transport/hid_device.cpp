#include "transport/hid_device.hpp"

#include <hidapi/hidapi.h>

#include <cerrno>
#include <cstring>
#include <cwchar>

#include "core/error.hpp"

namespace armctl::transport {
namespace {

std::string narrow(const wchar_t* w) {
  if (!w) return {};
  std::string out;
  for (; *w; ++w) out += (*w < 0x80) ? static_cast<char>(*w) : '?';
  return out;
}

void ensure_hidapi() {
  static const bool ok = hid_init() == 0;  // hid_exit is left to process exit
  if (!ok) throw ArmctlError(ErrorKind::io, "hidapi could not start (hid_init failed)");
}

std::string hid_error_text(hid_device_* dev) {
  const wchar_t* e = hid_error(dev);
  return e ? narrow(e) : "unknown hidapi error";
}

}  // namespace

std::vector<HidDeviceInfo> hid_enumerate(std::uint16_t vendor_id, std::uint16_t product_id) {
  ensure_hidapi();
  std::vector<HidDeviceInfo> out;
  hid_device_info* list = ::hid_enumerate(vendor_id, product_id);
  for (hid_device_info* d = list; d; d = d->next) {
    HidDeviceInfo info;
    info.path = d->path ? d->path : "";
    info.serial_number = narrow(d->serial_number);
    info.manufacturer = narrow(d->manufacturer_string);
    info.product = narrow(d->product_string);
    info.vendor_id = d->vendor_id;
    info.product_id = d->product_id;
    info.interface_number = d->interface_number;
    out.push_back(std::move(info));
  }
  hid_free_enumeration(list);
  return out;
}

namespace {

class HidapiBackend final : public HidBackend {
 public:
  std::vector<HidDeviceInfo> enumerate(std::uint16_t vendor_id, std::uint16_t product_id) override {
    return hid_enumerate(vendor_id, product_id);
  }
  std::unique_ptr<HidPort> open(const std::string& path) override {
    return std::make_unique<HidDevice>(path);
  }
};

}  // namespace

HidBackend& hidapi_backend() {
  static HidapiBackend backend;
  return backend;
}

HidDevice::HidDevice(const std::string& path) : path_(path), lock_(path) {
  ensure_hidapi();
  errno = 0;
  dev_ = hid_open_path(path.c_str());
  if (!dev_) {
    const int err = errno;
    std::string msg = "open HID device " + path + ": " +
                      (err ? std::string(std::strerror(err)) + " (errno " + std::to_string(err) + ")"
                           : std::string("hidapi could not open it"));
    if (err == EACCES) {
      msg += " — install udev/50-armctl.rules and re-plug the board (see docs/usb-hid.md)";
    }
    throw ArmctlError(ErrorKind::io, msg);
  }
}

HidDevice::~HidDevice() {
  if (dev_) hid_close(dev_);
}

void HidDevice::write(std::span<const std::uint8_t> report) {
  const int n = hid_write(dev_, report.data(), report.size());
  if (n < 0) {
    throw ArmctlError(ErrorKind::io, "write to HID device " + path_ + ": " + hid_error_text(dev_));
  }
}

std::size_t HidDevice::read(std::span<std::uint8_t> buffer, TimePoint deadline) {
  const auto left = deadline - clock_.now();
  const auto ms = std::chrono::ceil<std::chrono::milliseconds>(left).count();
  const int n = hid_read_timeout(dev_, buffer.data(), buffer.size(),
                                 ms > 0 ? static_cast<int>(std::min<long long>(ms, 1 << 30)) : 0);
  if (n < 0) {
    throw ArmctlError(ErrorKind::io, "read from HID device " + path_ + ": " + hid_error_text(dev_));
  }
  return static_cast<std::size_t>(n);
}

}  // namespace armctl::transport

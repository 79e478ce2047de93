// The fake xArm board under the transport seam (HidBackend/HidPort) on a SimClock, for SDK
// tests: reading advances simulated time to the next reply or the deadline; nothing sleeps.
// Opening it twice gives two handles that both get every reply, as on hidraw (the fake
// takes no lock: that is HidDevice's job, tested in hid_lock_test and cli_hid_test).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "fake_xarm_hid.hpp"
#include "transport/hid_device.hpp"

namespace armctl::testing {

class FakeHidBackend final : public transport::HidBackend {
 public:
  static constexpr const char* kPath = "/dev/hidraw-fake0";

  explicit FakeHidBackend(FakeHidBehaviour behaviour = {})
      : board_(clock_, std::move(behaviour)) {
    transport::HidDeviceInfo info;
    info.path = kPath;
    info.serial_number = "FAKE0001";
    info.manufacturer = "MyUSB_HID";
    info.product = "LOBOT";
    info.vendor_id = 0x0483;
    info.product_id = 0x5750;
    info.interface_number = 0;
    devices.push_back(info);
  }

  std::vector<transport::HidDeviceInfo> enumerate(std::uint16_t vendor_id,
                                                  std::uint16_t product_id) override {
    std::vector<transport::HidDeviceInfo> out;
    for (const auto& d : devices) {
      if ((vendor_id == 0 || d.vendor_id == vendor_id) &&
          (product_id == 0 || d.product_id == product_id)) {
        out.push_back(d);
      }
    }
    return out;
  }

  std::unique_ptr<transport::HidPort> open(const std::string& path) override {
    if (path != kPath) {
      throw ArmctlError(ErrorKind::io, "open HID device " + path + ": No such file or directory");
    }
    return std::make_unique<Port>(*this, board_.open());
  }

  SimClock& clock() { return clock_; }
  FakeXarmHid& board() { return board_; }
  std::vector<transport::HidDeviceInfo> devices;  // what enumerate lists

 private:
  class Port final : public transport::HidPort {
   public:
    Port(FakeHidBackend& backend, FakeXarmHid::Handle handle)
        : backend_(backend), handle_(handle) {}
    void write(std::span<const std::uint8_t> report) override { backend_.board_.write(report); }
    std::size_t read(std::span<std::uint8_t> buffer, TimePoint deadline) override {
      auto r = backend_.board_.read(handle_, deadline,
                                    [this](TimePoint t) { backend_.clock_.advance_to(t); });
      if (!r) return 0;
      const std::size_t n = std::min(buffer.size(), r->size());
      std::copy_n(r->begin(), n, buffer.begin());
      return n;
    }
    const std::string& path() const override { return path_; }
    const Clock& clock() const override { return backend_.clock_; }
    std::string other_users() const override {
      return backend_.board_.behaviour().other_opener_every > Duration::zero()
                 ? backend_.board_.behaviour().other_opener
                 : std::string();
    }

   private:
    FakeHidBackend& backend_;
    FakeXarmHid::Handle handle_;
    std::string path_ = kPath;
  };

  SimClock clock_;
  FakeXarmHid board_;
};

}  // namespace armctl::testing

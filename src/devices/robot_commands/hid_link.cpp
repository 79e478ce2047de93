#include "devices/robot_commands/hid_link.hpp"

#include <array>

#include "core/error.hpp"
#include "protocol/robot_commands/hid_report.hpp"

namespace armctl::robot_commands {

std::vector<transport::HidDeviceInfo> find_xarm_boards() {
  std::vector<transport::HidDeviceInfo> out;
  for (auto& d : transport::hid_enumerate(kXarmVendorId, kXarmProductId)) {
    if (d.product == kXarmProduct) out.push_back(std::move(d));
  }
  return out;
}

HidLink::HidLink(const std::string& path, std::string serial_number)
    : device_(path), serial_(std::move(serial_number)) {}

std::unique_ptr<HidLink> HidLink::open_board(const std::string& serial_or_path) {
  const auto boards = find_xarm_boards();
  if (boards.empty()) {
    throw ArmctlError(ErrorKind::io,
                      "no xArm board found on USB (looking for 0483:5750 \"LOBOT\"); check the "
                      "cable and `armctl list`");
  }
  for (const auto& b : boards) {
    if (serial_or_path.empty() || b.serial_number == serial_or_path || b.path == serial_or_path) {
      return std::make_unique<HidLink>(b.path, b.serial_number);
    }
  }
  std::string found;
  for (const auto& b : boards) {
    if (!found.empty()) found += ", ";
    found += b.path;
    found += " (serial " + b.serial_number + ")";
  }
  throw ArmctlError(ErrorKind::io, "no xArm board with serial number or path \"" +
                                       serial_or_path + "\"; found: " + found);
}

void HidLink::send(const rc::Frame& frame) { device_.write(rc::encode_hid_report(frame)); }

std::optional<rc::Frame> HidLink::receive(TimePoint deadline) {
  for (;;) {
    std::array<std::uint8_t, rc::kHidWriteSize> report{};
    const std::size_t n = device_.read(report, deadline);
    if (n == 0) return std::nullopt;
    auto frame = rc::decode_hid_report(std::span<const std::uint8_t>(report.data(), n));
    if (frame) return frame.value();
    ++discarded_;  // unreadable report: skip it, as the serial receiver skips garbage
    if (clock().now() >= deadline) return std::nullopt;
  }
}

std::string HidLink::describe() const {
  return "hid:" + device_.path() + (serial_.empty() ? "" : " (serial " + serial_ + ")");
}

}  // namespace armctl::robot_commands

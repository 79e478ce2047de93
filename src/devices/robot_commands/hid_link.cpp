#include "devices/robot_commands/hid_link.hpp"

#include <array>

#include <algorithm>

#include <fmt/core.h>

#include "core/error.hpp"
#include "protocol/robot_commands/hid_report.hpp"

namespace armctl::robot_commands {
namespace {

bool is_xarm(const transport::HidDeviceInfo& d) {
  return d.vendor_id == kXarmVendorId && d.product_id == kXarmProductId &&
         d.product == kXarmProduct;
}

}  // namespace

ClientOptions hid_client_options(int servo_count) {
  ClientOptions o;
  o.servo_count = servo_count;
  o.reply_timeout = std::chrono::milliseconds(1500);
  o.read_attempts = 3;
  o.poll_interval = std::chrono::milliseconds(500);
  o.servo_off_per_servo = true;
  return o;
}

std::vector<transport::HidDeviceInfo> find_xarm_boards(transport::HidBackend& backend) {
  std::vector<transport::HidDeviceInfo> out;
  for (auto& d : backend.enumerate(kXarmVendorId, kXarmProductId)) {
    if (is_xarm(d)) out.push_back(std::move(d));
  }
  return out;
}

HidLink::HidLink(std::unique_ptr<transport::HidPort> port, std::string serial_number)
    : port_(std::move(port)), serial_(std::move(serial_number)) {
  if (const auto others = port_->other_users(); !others.empty()) {
    warnings_.push_back(fmt::format(
        "{} is also open in {}: the board answers every program's requests on every handle, "
        "so replies can be mixed up; stop the other program (fwupd: sudo systemctl stop fwupd)",
        port_->path(), others));
  }
}

std::unique_ptr<HidLink> HidLink::open_board(const std::string& serial_or_path,
                                             transport::HidBackend& backend) {
  if (serial_or_path.rfind('/', 0) == 0) {
    // An explicit node: open it whatever it says it is, but say so if it is not an xArm.
    std::optional<transport::HidDeviceInfo> info;
    try {
      for (auto& d : backend.enumerate(0, 0)) {
        if (d.path == serial_or_path) info = std::move(d);
      }
    } catch (const ArmctlError&) {
      // Listing failed (e.g. no udev in a container): the named node may still open.
    }
    std::string note;
    if (!info) {
      note = fmt::format("{} is not listed as a HID device; opening it anyway", serial_or_path);
    } else if (!is_xarm(*info)) {
      note = fmt::format(
          "{} is {:04x}:{:04x} \"{}\", not an xArm board (0483:5750 \"{}\"); opening it anyway "
          "as you named it (clone boards exist)",
          serial_or_path, info->vendor_id, info->product_id, info->product, kXarmProduct);
    }
    auto link = std::make_unique<HidLink>(backend.open(serial_or_path),
                                          info ? info->serial_number : std::string());
    if (!note.empty()) link->warnings_.insert(link->warnings_.begin(), note);
    return link;
  }
  const auto boards = find_xarm_boards(backend);
  if (boards.empty()) {
    throw ArmctlError(ErrorKind::io,
                      "no xArm board found on USB (looking for 0483:5750 \"LOBOT\"); check the "
                      "cable and `armctl list` (it also says when a board has no hidraw node)");
  }
  for (const auto& b : boards) {
    if (serial_or_path.empty() || b.serial_number == serial_or_path) {
      return std::make_unique<HidLink>(backend.open(b.path), b.serial_number);
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

void HidLink::send(const rc::Frame& frame) { port_->write(rc::encode_hid_report(frame)); }

std::optional<rc::Frame> HidLink::receive(TimePoint deadline) {
  for (;;) {
    std::array<std::uint8_t, rc::kHidWriteSize> report{};
    const std::size_t n = port_->read(report, deadline);
    if (n == 0) return std::nullopt;
    auto frame = rc::decode_hid_report(std::span<const std::uint8_t>(report.data(), n));
    if (frame) return frame.value();
    ++discarded_;  // unreadable report: skip it, as the serial receiver skips garbage
    if (clock().now() >= deadline) return std::nullopt;
  }
}

std::string HidLink::describe() const {
  std::string d = "hid:" + port_->path();
  std::string extra;
  if (!serial_.empty()) extra = "serial " + serial_;
  if (const auto others = port_->other_users(); !others.empty()) {
    extra += (extra.empty() ? "" : "; ") + std::string("also open in ") + others;
  }
  return extra.empty() ? d : d + " (" + extra + ")";
}

Status await_first_contact(Client& client) {
  auto mv = client.battery_millivolts();
  if (mv) return Ok{};
  if (mv.error().kind != ErrorKind::timeout) return mv.error();
  return Error{ErrorKind::timeout,
               fmt::format("{}: the board did not answer its first request after opening. Is it "
                           "switched on? Is another program using it (fwupd: `systemctl status fwupd`)? See "
                           "docs/usb-hid.md",
                           mv.error().message)};
}

Duration HidLink::frame_time(std::size_t serial_bytes) const {
  const std::size_t reports = (serial_bytes + 63) / 64;
  const std::size_t servos = serial_bytes > 7 ? (serial_bytes - 7) / 3 : 0;
  return std::max<Duration>(std::chrono::milliseconds(1) * static_cast<std::int64_t>(reports),
                            wire_time(servos * 10, 115200));
}

}  // namespace armctl::robot_commands

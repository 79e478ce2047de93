// `armctl list`: attached xArm boards (USB HID) and serial ports, with what they are, and
// boards that are plugged in but cannot be used through hidraw, with the likely reason.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "apps/armctl/commands.hpp"
#include "apps/armctl/json_output.hpp"
#include "core/error.hpp"
#include "core/printable.hpp"
#include "devices/robot_commands/hid_link.hpp"
#include "devices/robot_commands/hid_link_sysfs.hpp"
#include "transport/hid_device.hpp"

namespace armctl::cli {
namespace {

namespace fs = std::filesystem;

struct PortInfo {
  std::string path;
  std::string target;  // for by-id links: the tty they point to
  std::string usb;     // "1a86:7523 QinHeng USB Serial", or "" if not USB
};

std::string read_line(const fs::path& p) {
  std::ifstream in(p);
  std::string s;
  std::getline(in, s);
  return s;
}

// Walks up from /sys/class/tty/NAME/device to the USB device that has idVendor.
std::string usb_description(const std::string& tty_name) {
  std::error_code ec;
  fs::path dev = fs::canonical(fs::path("/sys/class/tty") / tty_name / "device", ec);
  if (ec) return {};
  for (fs::path p = dev; !p.empty() && p != p.root_path(); p = p.parent_path()) {
    if (fs::exists(p / "idVendor", ec)) {
      std::string d = read_line(p / "idVendor") + ":" + read_line(p / "idProduct");
      for (const char* f : {"manufacturer", "product", "serial"}) {
        const std::string v = read_line(p / f);
        if (v.empty()) continue;
        d += std::string(f) == "serial" ? " serial " : " ";
        d += v;
      }
      return d;
    }
  }
  return {};
}

std::vector<PortInfo> serial_ports() {
  std::vector<PortInfo> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/dev", ec)) {
    const std::string name = entry.path().filename().string();
    for (const char* prefix : {"ttyUSB", "ttyACM", "ttyAMA"}) {
      if (name.rfind(prefix, 0) == 0) out.push_back({entry.path().string(), "", usb_description(name)});
    }
  }
  for (const auto& entry : fs::directory_iterator("/dev/serial/by-id", ec)) {
    std::error_code ec2;
    const auto target = fs::canonical(entry.path(), ec2);
    out.push_back({entry.path().string(), ec2 ? "" : target.string(),
                   ec2 ? "" : usb_description(target.filename().string())});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.path < b.path; });
  return out;
}

void run_list(bool json) {
  std::vector<transport::HidDeviceInfo> boards;
  std::string hid_problem;
  try {
    boards = robot_commands::find_xarm_boards();
  } catch (const ArmctlError& e) {
    hid_problem = e.what();
  }
  // Plugged in (sysfs) but not usable through hidraw: say why. Those hidapi listed are fine.
  std::vector<robot_commands::UsbBoard> unusable;
  for (auto& u : robot_commands::xarm_boards_on_usb()) {
    if (!u.problem.empty()) unusable.push_back(std::move(u));
  }
  const auto ports = serial_ports();
  if (json) {
    nlohmann::json j{{"hid_boards", nlohmann::json::array()},
                     {"serial_ports", nlohmann::json::array()}};
    for (const auto& b : boards) {
      j["hid_boards"].push_back({{"path", b.path},
                                 {"serial_number", b.serial_number},
                                 {"product", b.product},
                                 {"manufacturer", b.manufacturer},
                                 {"uri", "hid:" + (b.serial_number.empty() ? b.path : b.serial_number)}});
    }
    for (const auto& p : ports) {
      j["serial_ports"].push_back({{"path", p.path}, {"target", p.target}, {"usb", p.usb}});
    }
    if (!hid_problem.empty()) j["hid_problem"] = hid_problem;
    j["usb_boards_without_hidraw"] = nlohmann::json::array();
    for (const auto& u : unusable) {
      j["usb_boards_without_hidraw"].push_back({{"usb", u.usb_name},
                                                {"product", u.product},
                                                {"serial_number", u.serial},
                                                {"hidraw", u.hidraw},
                                                {"problem", u.problem}});
    }
    print_json_line(j);
    return;
  }
  fmt::print("xArm boards (USB HID 0483:5750 \"LOBOT\"):\n");
  // Names, serial numbers and paths come from the devices and sysfs: outside text (printable).
  if (!hid_problem.empty()) fmt::print("  (cannot enumerate: {})\n", printable(hid_problem));
  if (boards.empty()) fmt::print("  none found\n");
  for (const auto& u : unusable) {
    fmt::print("  USB {} (0483:5750 \"{}\"{}) is plugged in but not usable: {}\n", printable(u.usb_name),
               printable(u.product), u.serial.empty() ? "" : " serial " + printable(u.serial), printable(u.problem));
  }
  for (const auto& b : boards) {
    fmt::print("  {}  serial {}  {} {}  -> --device hid:{}\n", printable(b.path),
               b.serial_number.empty() ? "(none)" : printable(b.serial_number), printable(b.manufacturer), printable(b.product),
               printable(b.serial_number.empty() ? b.path : b.serial_number));
  }
  fmt::print("Serial ports:\n");
  if (ports.empty()) fmt::print("  none found\n");
  for (const auto& p : ports) {
    fmt::print("  {}{}{}\n", printable(p.path), p.target.empty() ? "" : " -> " + printable(p.target),
               p.usb.empty() ? "" : "  (USB " + printable(p.usb) + ")");
  }
}

}  // namespace

void add_list_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* list = app.add_subcommand("list", "Attached xArm boards (USB HID) and serial ports");
  list->add_flag("--json", *json, "Machine-readable output");
  list->callback([json] { run_list(*json); });
}

}  // namespace armctl::cli

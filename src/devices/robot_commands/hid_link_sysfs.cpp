#include "devices/robot_commands/hid_link_sysfs.hpp"

#include <algorithm>
#include <fstream>

#include <unistd.h>

namespace armctl::robot_commands {
namespace {

namespace fs = std::filesystem;

std::string read_line(const fs::path& p) {
  std::ifstream in(p);
  std::string s;
  std::getline(in, s);
  return s;
}

constexpr const char* kFwupdHint =
    "fwupd is known to take or remove this board's node: check `systemctl status fwupd`, stop "
    "it with `sudo systemctl stop fwupd` (or `sudo systemctl mask fwupd`), then re-plug the "
    "board";

std::string problem_of(const UsbBoard& b, const fs::path& dev_root) {
  if (!b.hid_driver_bound) {
    return std::string("its HID interface has no driver bound (usbhid not loaded, or another "
                       "program detached it; ") + kFwupdHint + ")";
  }
  if (b.hidraw.empty()) {
    return std::string("usbhid is bound but the kernel made no hidraw node (hidraw support "
                       "missing, or another program holds the interface; ") + kFwupdHint + ")";
  }
  std::string why;
  for (const auto& h : b.hidraw) {
    const fs::path node = dev_root / h;
    std::error_code ec;
    if (!fs::exists(node, ec)) {
      why = node.string() + " does not exist (udev made no node; in a container, pass the "
                            "device through)";
      continue;
    }
    if (::access(node.c_str(), R_OK | W_OK) != 0) {
      why = node.string() + " is not readable and writable by you (install "
                            "udev/50-armctl.rules and re-plug the board)";
      continue;
    }
    return {};  // one usable node is enough
  }
  return why;
}

}  // namespace

std::vector<UsbBoard> xarm_boards_on_usb(const fs::path& sysfs_root, const fs::path& dev_root) {
  std::vector<UsbBoard> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(sysfs_root / "bus/usb/devices", ec)) {
    const fs::path dev = entry.path();
    if (read_line(dev / "idVendor") != "0483" || read_line(dev / "idProduct") != "5750") continue;
    UsbBoard b;
    b.usb_name = dev.filename().string();
    b.product = read_line(dev / "product");
    b.serial = read_line(dev / "serial");
    // Interfaces ("1-1.2:1.0") are subdirectories; hidraw nodes sit below them as
    // .../0003:0483:5750.000N/hidraw/hidrawM. Symlinks (driver, subsystem) are not followed.
    std::error_code walk_ec;
    const fs::path real = fs::canonical(dev, walk_ec);
    if (walk_ec) continue;
    for (auto it = fs::recursive_directory_iterator(real, walk_ec);
         !walk_ec && it != fs::recursive_directory_iterator(); it.increment(walk_ec)) {
      const std::string name = it->path().filename().string();
      if (it->is_symlink(walk_ec) && name == "driver") {
        std::error_code link_ec;
        if (fs::read_symlink(it->path(), link_ec).filename() == "usbhid") b.hid_driver_bound = true;
      } else if (name.rfind("hidraw", 0) == 0 && name != "hidraw" &&
                 it->path().parent_path().filename() == "hidraw") {
        b.hidraw.push_back(name);
      }
      if (it.depth() > 4) it.disable_recursion_pending();
    }
    std::sort(b.hidraw.begin(), b.hidraw.end());
    b.problem = problem_of(b, dev_root);
    out.push_back(std::move(b));
  }
  std::sort(out.begin(), out.end(),
            [](const UsbBoard& a, const UsbBoard& c) { return a.usb_name < c.usb_name; });
  return out;
}

}  // namespace armctl::robot_commands

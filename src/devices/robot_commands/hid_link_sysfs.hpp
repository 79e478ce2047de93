// xArm boards as the kernel sees them on USB (sysfs), whether or not hidapi can list them:
// `armctl list` uses this to say why a board that is plugged in has no usable hidraw node
// (no driver bound, fwupd or another program detached it, udev made no /dev node, no
// permission). Linux only; an unreadable sysfs simply yields nothing.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace armctl::robot_commands {

struct UsbBoard {
  std::string usb_name;  // sysfs name, e.g. "1-1.2"
  std::string product;   // USB product string ("LOBOT" on xArm boards)
  std::string serial;
  bool hid_driver_bound = false;     // an interface is bound to usbhid
  std::vector<std::string> hidraw;   // "hidraw3": hidraw nodes the kernel made for it
  // Why it cannot be used through hidraw, or "" if a /dev node exists and is accessible.
  std::string problem;
};

// Every USB device 0483:5750 under `sysfs_root`/bus/usb/devices; /dev nodes are looked up
// under `dev_root` (both are parameters for tests).
std::vector<UsbBoard> xarm_boards_on_usb(const std::filesystem::path& sysfs_root = "/sys",
                                         const std::filesystem::path& dev_root = "/dev");

}  // namespace armctl::robot_commands

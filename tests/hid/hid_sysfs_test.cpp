// `armctl list`'s view of USB (hid_link_sysfs.hpp) on fake sysfs and /dev trees: a board
// with a usable node, one whose interface has no driver, one with no hidraw, one whose
// /dev node udev never made, and a device that is not 0483:5750.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "devices/robot_commands/hid_link_sysfs.hpp"

namespace armctl::robot_commands {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text << "\n";
}

class FakeSysfs : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("armctl-sysfs-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "sys/bus/usb/devices");
    fs::create_directories(root_ / "dev");
    fs::create_directories(root_ / "sys/bus/usb/drivers/usbhid");
  }
  void TearDown() override { fs::remove_all(root_); }

  // A USB device under sys/devices, linked from bus/usb/devices like the kernel does.
  fs::path device(const std::string& name, const std::string& vid, const std::string& pid,
                  bool bound, const std::string& hidraw) {
    const fs::path dev = root_ / "sys/devices/pci0000:00/usb1" / name;
    write(dev / "idVendor", vid);
    write(dev / "idProduct", pid);
    write(dev / "product", "LOBOT");
    write(dev / "serial", "SER-" + name);
    const fs::path intf = dev / (name + ":1.0");
    fs::create_directories(intf);
    if (bound) fs::create_directory_symlink(root_ / "sys/bus/usb/drivers/usbhid", intf / "driver");
    if (!hidraw.empty()) fs::create_directories(intf / "0003:0483:5750.0001/hidraw" / hidraw);
    fs::create_directory_symlink(dev, root_ / "sys/bus/usb/devices" / name);
    return dev;
  }

  fs::path root_;
};

TEST_F(FakeSysfs, EachBoardGetsItsReason) {
  device("1-1", "0483", "5750", true, "hidraw0");  // fine
  write(root_ / "dev/hidraw0", "");
  device("1-2", "0483", "5750", false, "");         // no driver (fwupd detached it?)
  device("1-3", "0483", "5750", true, "");          // bound, no hidraw
  device("1-4", "0483", "5750", true, "hidraw5");   // no /dev node
  device("1-5", "1a86", "7523", true, "");          // a USB-serial adapter: not listed
  const auto boards = xarm_boards_on_usb(root_ / "sys", root_ / "dev");
  ASSERT_EQ(boards.size(), 4u);
  EXPECT_EQ(boards[0].usb_name, "1-1");
  EXPECT_EQ(boards[0].hidraw, std::vector<std::string>{"hidraw0"});
  EXPECT_TRUE(boards[0].problem.empty()) << boards[0].problem;
  EXPECT_EQ(boards[0].serial, "SER-1-1");
  EXPECT_FALSE(boards[1].hid_driver_bound);
  EXPECT_NE(boards[1].problem.find("no driver bound"), std::string::npos) << boards[1].problem;
  EXPECT_NE(boards[1].problem.find("sudo systemctl stop fwupd"), std::string::npos);
  EXPECT_NE(boards[2].problem.find("no hidraw node"), std::string::npos) << boards[2].problem;
  EXPECT_NE(boards[3].problem.find("hidraw5 does not exist"), std::string::npos)
      << boards[3].problem;
}

TEST_F(FakeSysfs, NoSysfsMeansNoBoards) {
  EXPECT_TRUE(xarm_boards_on_usb(root_ / "nothing", root_ / "dev").empty());
}

}  // namespace
}  // namespace armctl::robot_commands

// The evdev gamepad source (jog/evdev_gamepad.hpp) where this machine allows (it has no
// input devices and no uinput): what --gamepad accepts, a file that is no input device
// refused, and a pad not plugged in yet waited for without blocking.
#include "jog/evdev_gamepad.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace armctl::jog {
namespace {

TEST(EvdevGamepad, TakesAutoOrAPath) {
  auto r = EvdevGamepad::open("joystick");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_argument);
  EXPECT_EQ(r.error().message,
            "--gamepad 'joystick': 'auto' (the first gamepad found) or a device's path such as /dev/input/event5");
  EXPECT_TRUE(EvdevGamepad::open("auto"));
}

TEST(EvdevGamepad, AFileThatIsNoInputDeviceIsRefused) {
  const auto path = std::filesystem::temp_directory_path() / ("armctl-not-a-pad-" + std::to_string(::getpid()));
  std::ofstream(path) << "not a pad";
  auto r = EvdevGamepad::open(path.string());
  std::filesystem::remove(path);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_argument);
  EXPECT_NE(r.error().message.find("gamepad " + path.string() + ": not an input device"), std::string::npos)
      << r.error().message;
}

TEST(EvdevGamepad, APadNotPluggedInYetIsWaitedFor) {
  auto r = EvdevGamepad::open("/dev/input/event-armctl-test");
  ASSERT_TRUE(r) << r.error().message;
  EvdevGamepad& pad = **r;
  const PadPoll p = pad.poll(TimePoint{});
  EXPECT_FALSE(p.connected);
  EXPECT_TRUE(p.events.empty());
  EXPECT_FALSE(p.unplugged);
  EXPECT_FALSE(p.ended);  // a device never ends: the session waits for it
  EXPECT_EQ(pad.description(), "no gamepad on /dev/input/event-armctl-test yet (looking every second)");
}

}  // namespace
}  // namespace armctl::jog

// A gamepad through Linux evdev (/dev/input/eventN, read with libevdev; docs/gamepad.md).
// Given `auto`, the first device that has a gamepad's left stick (ABS_X, ABS_Y) and face
// buttons (BTN_SOUTH); given a path, that device. Hot-plug: while there is none (not yet
// plugged in, or unplugged: a read fails with ENODEV) it looks again every second, and a pad
// plugged in is picked up. Reads never wait.
#pragma once

#include <memory>
#include <string>

#include "core/error.hpp"
#include "jog/gamepad_source.hpp"

struct libevdev;

namespace armctl::jog {

class EvdevGamepad final : public GamepadSource {
 public:
  // `device`: "auto" or a device's path such as /dev/input/event5 (or a udev link to it).
  // Errors: anything else (invalid_argument); a path that exists but is not a gamepad
  // (invalid_argument) or that this user may not read (io); `auto` where this user may read
  // none of the input devices (io). A path that does not exist yet is waited for.
  static Result<std::unique_ptr<EvdevGamepad>> open(const std::string& device);
  ~EvdevGamepad() override;

  PadPoll poll(TimePoint now) override;
  std::string description() const override;

  static constexpr Duration kLookAgain = std::chrono::seconds(1);

 private:
  explicit EvdevGamepad(std::string device) : device_(std::move(device)) {}
  void look(PadPoll& p);
  void close_device();

  std::string device_;  // "auto" or a path
  std::string path_;    // the device open now
  int fd_ = -1;
  libevdev* dev_ = nullptr;
  std::optional<TimePoint> last_look_;
};

}  // namespace armctl::jog

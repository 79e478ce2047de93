#include "jog/evdev_gamepad.hpp"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "core/printable.hpp"

namespace armctl::jog {
namespace {

bool is_gamepad(const libevdev* d) {
  return libevdev_has_event_code(d, EV_ABS, ABS_X) && libevdev_has_event_code(d, EV_ABS, ABS_Y) &&
         libevdev_has_event_code(d, EV_KEY, BTN_SOUTH);
}

PadDescription description_of(const libevdev* d) {
  PadDescription pad;
  pad.name = printable(libevdev_get_name(d) ? libevdev_get_name(d) : "");
  for (unsigned code = 0; code <= ABS_MAX; ++code)
    if (const input_absinfo* a = libevdev_get_abs_info(d, code))
      pad.axes[std::uint16_t(code)] = PadAxis{a->minimum, a->maximum, a->value};
  return pad;
}

// Why `path` is not a pad we can read, or nothing when it is one (then `fd` and `dev` are it).
std::optional<Error> open_pad(const std::string& path, int& fd, libevdev*& dev) {
  fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int e = errno;
    std::string why = std::strerror(e);
    if (e == EACCES)
      why += " (this user may not read input devices: add it to the group 'input', then log in again)";
    return Error{ErrorKind::io, fmt::format("gamepad {}: {}", printable(path), why)};
  }
  if (int rc = libevdev_new_from_fd(fd, &dev); rc < 0) {
    ::close(fd);
    fd = -1;
    dev = nullptr;
    return Error{ErrorKind::invalid_argument,
                 fmt::format("gamepad {}: not an input device ({})", printable(path), std::strerror(-rc))};
  }
  if (!is_gamepad(dev)) {
    Error e{ErrorKind::invalid_argument,
            fmt::format("{} ('{}') is not a gamepad: a gamepad has a left stick (ABS_X, ABS_Y) and face "
                        "buttons (BTN_SOUTH)",
                        printable(path), printable(libevdev_get_name(dev) ? libevdev_get_name(dev) : ""))};
    libevdev_free(dev);
    ::close(fd);
    fd = -1;
    dev = nullptr;
    return e;
  }
  return std::nullopt;
}

// /dev/input/event* in the order of their numbers (event2 before event10).
std::vector<std::string> event_devices() {
  std::vector<std::pair<int, std::string>> found;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/input", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("event", 0) != 0) continue;
    found.emplace_back(std::atoi(name.c_str() + 5), entry.path().string());
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> paths;
  for (auto& [n, path] : found) paths.push_back(std::move(path));
  return paths;
}

}  // namespace

Result<std::unique_ptr<EvdevGamepad>> EvdevGamepad::open(const std::string& device) {
  if (device != "auto" && device.rfind('/', 0) != 0)
    return Error{ErrorKind::invalid_argument,
                 fmt::format("--gamepad '{}': 'auto' (the first gamepad found) or a device's path such as "
                             "/dev/input/event5",
                             printable(device))};
  std::unique_ptr<EvdevGamepad> pad(new EvdevGamepad(device));
  if (device == "auto") {
    // Input devices there but none readable: no pad plugged in later could be read either.
    const std::vector<std::string> paths = event_devices();
    const bool refused = !paths.empty() && std::all_of(paths.begin(), paths.end(), [](const std::string& p) {
      return ::access(p.c_str(), R_OK) != 0 && errno == EACCES;
    });
    if (refused)
      return Error{ErrorKind::io,
                   fmt::format("--gamepad auto: this user may read none of the {} input devices under /dev/input: "
                               "add it to the group 'input', then log in again",
                               paths.size())};
  } else {
    // A pad not plugged in yet is waited for; one that cannot be read or is no pad is an
    // error now, not a silent wait for ever.
    int fd = -1;
    libevdev* dev = nullptr;
    if (auto why = open_pad(device, fd, dev)) {
      if (!std::filesystem::exists(device)) return pad;
      return *why;
    }
    libevdev_free(dev);
    ::close(fd);
  }
  return pad;
}

EvdevGamepad::~EvdevGamepad() { close_device(); }

void EvdevGamepad::close_device() {
  if (dev_) libevdev_free(dev_);
  if (fd_ >= 0) ::close(fd_);
  dev_ = nullptr;
  fd_ = -1;
  path_.clear();
}

void EvdevGamepad::look(PadPoll& p) {
  const std::vector<std::string> paths = device_ == "auto" ? event_devices() : std::vector<std::string>{device_};
  for (const std::string& path : paths) {
    if (open_pad(path, fd_, dev_)) continue;  // not (yet) a pad we can read: the next look tries again
    path_ = path;
    p.connected = description_of(dev_);
    return;
  }
}

PadPoll EvdevGamepad::poll(TimePoint now) {
  PadPoll p;
  if (!dev_) {
    if (last_look_ && now - *last_look_ < kLookAgain) return p;
    last_look_ = now;
    look(p);
    if (!dev_) return p;
  }
  // After lost events (SYN_DROPPED) libevdev hands over the differences to the device's
  // state now (read with the sync flag until EAGAIN), then normal events again.
  unsigned flag = LIBEVDEV_READ_FLAG_NORMAL;
  input_event ev{};
  for (;;) {
    const int rc = libevdev_next_event(dev_, flag, &ev);
    if (rc == LIBEVDEV_READ_STATUS_SUCCESS || rc == LIBEVDEV_READ_STATUS_SYNC) {
      p.events.push_back(PadEvent{ev.type, ev.code, ev.value, now});
      if (rc == LIBEVDEV_READ_STATUS_SYNC) flag = LIBEVDEV_READ_FLAG_SYNC;
    } else if (rc == -EAGAIN && flag == LIBEVDEV_READ_FLAG_SYNC) {
      flag = LIBEVDEV_READ_FLAG_NORMAL;
    } else if (rc == -EAGAIN) {
      break;
    } else {
      // ENODEV (unplugged) or any other failed read: the pad is gone; look again later.
      p.unplugged = true;
      close_device();
      last_look_ = now;
      break;
    }
  }
  return p;
}

std::string EvdevGamepad::description() const {
  if (dev_) return fmt::format("gamepad '{}' on {}", printable(libevdev_get_name(dev_)), path_);
  return device_ == "auto" ? "no gamepad yet (looking under /dev/input every second)"
                           : fmt::format("no gamepad on {} yet (looking every second)", printable(device_));
}

}  // namespace armctl::jog

// hidapi's C functions, replaced for `armctl_fake_hid` (armctl linked with this file): one
// fake xArm board (fake_xarm_hid.hpp) on the steady clock, so the CLI's real HID path (the
// node lock, HidDevice, HidLink, the session, `watch`) runs end to end with no hardware.
// Definitions in the executable take precedence over libhidapi's. Set by the test:
//   ARMCTL_FAKE_HID_NODE       the "hidraw node": a file the test created (armctl locks it)
//   ARMCTL_FAKE_HID_PRODUCT    product string (default LOBOT)
//   ARMCTL_FAKE_HID_BEHAVIOUR  parse_fake_hid_behaviour() text
//   ARMCTL_FAKE_HID_LOG        appended after every report written: what the board holds
// Without ARMCTL_FAKE_HID_NODE no device is listed.
#include <hidapi/hidapi.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>

#include "fake_xarm_hid.hpp"

namespace {

using armctl::testing::FakeXarmHid;

std::string env(const char* name, const char* fallback = "") {
  const char* v = std::getenv(name);
  return v ? v : fallback;
}

wchar_t* wide(const std::string& s) {
  auto* w = static_cast<wchar_t*>(std::calloc(s.size() + 1, sizeof(wchar_t)));
  for (std::size_t i = 0; i < s.size(); ++i) w[i] = static_cast<unsigned char>(s[i]);
  return w;
}

struct FakeDevice {
  armctl::SteadyClock clock;
  FakeXarmHid board{clock, armctl::testing::parse_fake_hid_behaviour(env("ARMCTL_FAKE_HID_BEHAVIOUR"))};
  FakeXarmHid::Handle handle = board.open();
};

void log_state(FakeDevice& d) {
  const std::string path = env("ARMCTL_FAKE_HID_LOG");
  if (path.empty()) return;
  std::FILE* f = std::fopen(path.c_str(), "a");
  if (!f) return;
  const auto& r = d.board.requests().back();
  std::fprintf(f, "cmd=%u count=%u torque=", r.cmd, r.data.empty() ? 0u : r.data[0]);
  for (std::uint8_t s = 1; s <= 6; ++s) std::fprintf(f, "%d", d.board.servos().torque(s) ? 1 : 0);
  std::fprintf(f, " ignored=%d dropped=%d\n", d.board.ignored_requests(), d.board.replies_dropped());
  std::fclose(f);
}

}  // namespace

struct hid_device_ {
  FakeDevice fake;
};

extern "C" {

int hid_init(void) { return 0; }
int hid_exit(void) { return 0; }

hid_device_info* hid_enumerate(unsigned short vendor_id, unsigned short product_id) {
  const std::string node = env("ARMCTL_FAKE_HID_NODE");
  if (node.empty()) return nullptr;
  if ((vendor_id && vendor_id != 0x0483) || (product_id && product_id != 0x5750)) return nullptr;
  auto* d = static_cast<hid_device_info*>(std::calloc(1, sizeof(hid_device_info)));
  d->path = strdup(node.c_str());
  d->vendor_id = 0x0483;
  d->product_id = 0x5750;
  d->serial_number = wide("FAKE0001");
  d->manufacturer_string = wide("MyUSB_HID");
  d->product_string = wide(env("ARMCTL_FAKE_HID_PRODUCT", "LOBOT"));
  d->interface_number = 0;
  return d;
}

void hid_free_enumeration(hid_device_info* devs) {
  while (devs) {
    hid_device_info* next = devs->next;
    std::free(devs->path);
    std::free(devs->serial_number);
    std::free(devs->manufacturer_string);
    std::free(devs->product_string);
    std::free(devs);
    devs = next;
  }
}

hid_device* hid_open_path(const char* path) {
  if (env("ARMCTL_FAKE_HID_NODE") != path) {
    errno = ENOENT;
    return nullptr;
  }
  return new hid_device_;
}

void hid_close(hid_device* dev) { delete dev; }

int hid_write(hid_device* dev, const unsigned char* data, size_t length) {
  dev->fake.board.write(std::span<const std::uint8_t>(data, length));
  log_state(dev->fake);
  return static_cast<int>(length);
}

int hid_read_timeout(hid_device* dev, unsigned char* data, size_t length, int milliseconds) {
  const armctl::TimePoint deadline =
      dev->fake.clock.now() + std::chrono::milliseconds(milliseconds < 0 ? 1 << 30 : milliseconds);
  // The fake device's own latency: block like hid_read_timeout does on a real node.
  auto r = dev->fake.board.read(dev->fake.handle, deadline, [](armctl::TimePoint t) {
    std::this_thread::sleep_until(std::chrono::steady_clock::time_point(
        std::chrono::duration_cast<std::chrono::steady_clock::duration>(t.time_since_epoch())));
  });
  if (!r) return 0;
  const std::size_t n = std::min(length, r->size());
  std::memcpy(data, r->data(), n);
  return static_cast<int>(n);
}

const wchar_t* hid_error(hid_device*) { return L"fake hidapi error"; }

}  // extern "C"

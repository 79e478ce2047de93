// The portable core over a RAM standing in for the Mega's EEPROM (groups and servo
// settings), fed by scripted joints: shared by group_test.cpp and servo_settings_test.cpp.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "fake_joints.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/rc_codes.hpp"
#include "portable_controller/scara_arm.hpp"

namespace armctl::controller::testing {

// RAM standing in for the EEPROM. `writes_left` < 0: unlimited; else the memory takes that
// many more byte writes and then ignores the rest (power lost mid-way).
class RamMemory final : public GroupMemory {
 public:
  explicit RamMemory(std::uint32_t size = 4096) : bytes(size, 0xFF) {}
  std::uint32_t size() const override { return static_cast<std::uint32_t>(bytes.size()); }
  std::uint8_t read(std::uint32_t a) override { return bytes.at(a); }
  bool ready() override { return true; }
  void write(std::uint32_t a, std::uint8_t v) override {
    ++writes;
    if (writes_left == 0) return;
    if (writes_left > 0) --writes_left;
    bytes.at(a) = v;
  }
  std::vector<std::uint8_t> bytes;
  long writes_left = -1;
  long writes = 0;
};

struct Action {
  std::uint16_t ms;
  std::vector<std::pair<int, int>> targets;  // servo, position
};

struct GroupRig {
  explicit GroupRig(RamMemory& m) : memory(m) {
    core.begin(scara_joints, scara_joint_count, &joints, &upstream, 115200, now, &memory);
    run_us(100000);
    joints.log.clear();
    upstream.frames.clear();
  }
  void run_us(std::uint32_t us) { run_core(core, joints, now, us, 50); }
  void send(std::uint8_t command, std::vector<std::uint8_t> data) {
    core.on_frame(command, data.data(), static_cast<std::uint8_t>(data.size()), now);
    run_us(2000);
  }
  // The SDK's download sequence; true if every sub was acknowledged.
  bool download(std::uint8_t group, const std::vector<Action>& actions) {
    upstream.frames.clear();
    std::vector<std::uint8_t> begin{1, group};
    for (std::size_t left = actions.size(); left > 0;) {
      const std::size_t b = std::min<std::size_t>(left, 255);
      begin.push_back(static_cast<std::uint8_t>(b));
      left -= b;
    }
    send(rc_group_download, begin);
    send(rc_group_download, {2, group, 0, static_cast<std::uint8_t>(actions[0].targets.size()), 0});
    std::vector<std::uint8_t> blocks{3, group, 0};
    for (std::size_t b = 0; b * 255 < actions.size(); ++b) blocks.push_back(static_cast<std::uint8_t>(b));
    send(rc_group_download, blocks);
    for (std::size_t i = 0; i < actions.size(); ++i) {
      const Action& a = actions[i];
      std::vector<std::uint8_t> d{4, group, static_cast<std::uint8_t>(i / 255), static_cast<std::uint8_t>(i % 255),
                                  static_cast<std::uint8_t>(2 + 3 * a.targets.size()),
                                  static_cast<std::uint8_t>(a.ms & 0xFF), static_cast<std::uint8_t>(a.ms >> 8)};
      for (auto [s, p] : a.targets) {
        d.push_back(static_cast<std::uint8_t>(s));
        d.push_back(static_cast<std::uint8_t>(p & 0xFF));
        d.push_back(static_cast<std::uint8_t>(p >> 8));
      }
      send(rc_group_download, d);
    }
    send(rc_group_download, {5, group});
    return acks() == 4 + actions.size();
  }
  std::size_t acks() const {
    std::size_t n = 0;
    for (const auto& f : upstream.frames) n += f.command == rc_group_download ? 1 : 0;
    return n;
  }

  RamMemory& memory;
  FakeJoints joints;
  RecordingUpstream upstream;
  ControllerCore core;
  std::uint32_t now = 1000;
};

}  // namespace armctl::controller::testing

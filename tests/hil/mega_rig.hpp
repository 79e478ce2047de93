// Test rig for the Mega controller on emulated silicon: the Robot Commands SDK
// (robot_commands::Client) -> the Mega firmware on an emulated ATmega2560 (UART0 with wire
// timing) -> the simulated joint bus -> seven emulated ATmega328P joints and their motors
// (joint_avr::AvrMegaArm). One thread, simulated time: the SDK waiting for a reply runs the
// emulation, so every test is deterministic.
#pragma once

#include <memory>
#include <optional>
#include <set>
#include <string>

#include "arm_backends.hpp"
#include "devices/joint_avr/avr_mega_arm.hpp"
#include "devices/robot_commands/client.hpp"
#include "protocol/robot_commands/frame_receiver.hpp"

namespace armctl::hil {

class MegaRcLink final : public robot_commands::RcLink {
 public:
  explicit MegaRcLink(joint_avr::AvrMegaArm& mega) : mega_(mega) {}
  void send(const rc::Frame& frame) override { send_bytes(rc::encode_frame(frame)); }
  void send_bytes(const std::vector<std::uint8_t>& bytes) { mega_.send_upstream(bytes); }
  std::optional<rc::Frame> receive(TimePoint deadline) override {
    for (;;) {
      for (const joint_avr::UpstreamByte& b : mega_.take_upstream()) receiver_.feed_byte(b.value);
      if (auto f = receiver_.next()) return f;
      if (mega_.now() >= deadline) return std::nullopt;
      mega_.run_until(std::min(deadline, mega_.now() + std::chrono::microseconds(500)));
    }
  }
  const Clock& clock() const override { return mega_.arm().link().clock(); }
  std::string describe() const override { return "emulated Mega controller"; }
  Duration frame_time(std::size_t serial_bytes) const override {
    return wire_time(serial_bytes, mega_.upstream_baud());
  }

 private:
  joint_avr::AvrMegaArm& mega_;
  rc::FrameReceiver receiver_;
};

// Position -> clicks on the SCARA's lines (config/scara-arm.json).
inline int clicks_for(int joint, int position) {
  const int span = joint <= 3 ? 40000 : joint <= 6 ? 20000 : 10000;
  return -span / 2 + span * position / 1000;
}

struct MegaRig {
  // `leads_swapped`: joints whose motor leads are swapped (they run away, and stop
  // themselves with a fault).
  // `elf`: another Mega image built for `baud` (e.g. mega_firmware_elf_battery()).
  explicit MegaRig(std::uint32_t baud = 9600, const std::set<int>& leads_swapped = {}, std::string elf = {})
      : mega(hil_arm_config(baud, leads_swapped),
             !elf.empty()      ? elf
             : baud == 115200 ? joint_avr::mega_firmware_elf_115200()
                              : joint_avr::default_mega_firmware_elf(),
             baud),
        link(mega) {
    robot_commands::ClientOptions options;
    options.servo_count = 7;
    options.reply_timeout = std::chrono::milliseconds(500);
    client = std::make_unique<robot_commands::Client>(link, options);
    // Power-up: the joints read their EEPROM, the Mega sends set_zone and set_speed 0 to
    // each joint and polls every position once.
    mega.advance(std::chrono::milliseconds(400));
  }
  TimePoint now() const { return mega.now(); }
  // The joint's true position (the emulated encoder), not what the controller read.
  int clicks(int joint) { return int(std::lround(mega.arm().joint(joint).hardware().position_clicks())); }
  std::uint8_t mega_data(std::uint16_t address) { return mega.mega().read_data(address); }

  joint_avr::AvrMegaArm mega;
  MegaRcLink link;
  std::unique_ptr<robot_commands::Client> client;
};

}  // namespace armctl::hil

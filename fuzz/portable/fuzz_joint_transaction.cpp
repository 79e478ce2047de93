// libFuzzer target: random select edges, bytes, silences, encoder edges, control ticks and
// TX pops into one JointController. Invariants checked after every event:
//  - TX is enabled only while selected, or while the STATUS of a transaction whose select
//    just fell is still going out, and never longer than the timeout after select fell;
//  - next_tx_byte() never hands out a byte while TX is not enabled;
//  - the H-bridge duty stays within +-pwm_max and is 0 whenever the bridge is disabled;
//  - a joint holding a fault drives nothing (duty 0: braking, then bridge off);
// and at the end the joint must serve a clean ping transaction byte-exactly. Byte 1 also
// picks legacy-master mode (after select falls it may still receive COMMAND/DATA, each
// byte within the timeout of the last) and the motor polarity.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "portable/joint_controller.hpp"

using armctl::joint_bus::BusTransaction;
using armctl::joint_bus::DriveOutput;
using armctl::joint_bus::JointController;

namespace {
void check(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::uint8_t number = static_cast<std::uint8_t>(1 + data[0] % 7);
  const std::uint32_t baud = (data[1] & 1) ? 115200u : 9600u;
  armctl::joint_bus::JointOptions options;
  options.legacy_master = (data[1] & 2) != 0;
  options.polarity = (data[1] & 4) ? armctl::joint_bus::MotorPolarity::reversed
                                   : armctl::joint_bus::MotorPolarity::original;
  JointController joint;
  check(joint.begin(number, armctl::joint_bus::default_tuning(), baud, options));
  joint.init_encoder(false, false);
  const std::uint32_t timeout = joint.transaction().timeout_us();

  std::uint32_t now = 0xFFFF0000u;  // crosses the uint32 wrap early
  bool selected = false;
  std::uint32_t fell_at = 0;
  bool a = false, b = false;
  for (std::size_t i = 2; i < size; ++i) {
    const std::uint8_t op = data[i];
    switch (op >> 5) {
      case 0:
        selected = !selected;
        if (!selected) fell_at = now;
        joint.on_select(selected, now);
        break;
      case 1:
      case 2:
        if (i + 1 < size) joint.on_rx_byte(data[++i], now);
        break;
      case 3: {
        std::uint8_t out;
        const bool enabled = joint.tx_enabled();
        check(!joint.next_tx_byte(&out) || enabled);
        break;
      }
      case 4:
        now += static_cast<std::uint32_t>(op & 0x1F) * 97u;
        break;
      case 5:
        now += static_cast<std::uint32_t>(op & 0x1F) * (timeout / 8u);
        break;
      case 6:
        // Encoder edges, valid or not (bit 4 set: change both channels at once).
        if (op & 0x10) {
          a = !a;
          b = !b;
        } else if (op & 1) {
          a = !a;
        } else {
          b = !b;
        }
        joint.on_encoder_edge(a, b);
        break;
      default: {
        const DriveOutput out = joint.control_tick();
        check(out.duty <= 255 && out.duty >= -255);
        check(out.enable || out.duty == 0);
        if (joint.faults() != 0) check(out.duty == 0);  // braking (enabled) or off
        break;
      }
    }
    joint.poll(now);
    if (joint.tx_enabled()) {
      check(selected || joint.transaction().state() == BusTransaction::State::send_status);
      // Legacy: up to 4 more bytes (COMMAND, DATA), each within the timeout of the last.
      const std::uint32_t windows = options.legacy_master ? 5u : 1u;
      if (!selected) check(now - fell_at <= windows * (timeout + 31u * (timeout / 8u)));
    }
    check(joint.transaction().selected() == selected);
  }

  // Recovery: release select, let every timeout pass, then a clean ping must work.
  if (selected) joint.on_select(false, now);
  now += timeout + 1;
  joint.poll(now);
  check(!joint.tx_enabled());
  joint.on_select(true, now);
  std::uint8_t out[8];
  int n = 0;
  while (n < 8 && joint.next_tx_byte(&out[n])) ++n;
  check(n == 2 && out[0] == number && out[1] == 0);
  const std::uint8_t ping[4] = {0x00, 0x00, 0x34, 0x12};
  for (std::uint8_t byte : ping) joint.on_rx_byte(byte, ++now);
  n = 0;
  while (n < 8 && joint.next_tx_byte(&out[n])) ++n;
  check(n == 2 && out[0] == 0x34 && out[1] == 0x12);
  joint.on_select(false, ++now);
  n = 0;
  while (n < 8 && joint.next_tx_byte(&out[n])) ++n;
  check(n == 2 && out[0] == (options.legacy_master ? 0 : 100) && out[1] == 0);
  check(!joint.tx_enabled());
  return 0;
}

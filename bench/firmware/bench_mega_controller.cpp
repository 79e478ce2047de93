// Mega controller budgets: flash and static RAM from the ELF (limits: 64 KiB and 4 KiB of
// the ATmega2560's 8 KiB), and on emulated silicon (the Mega ELF on an emulated ATmega2560
// driving seven emulated joints, joint_avr::AvrMegaArm) at 9600 and 115200 baud:
//   mega_refresh_<baud>     position sweeps of all seven joints per second, idle upstream,
//                           against the joint bus floor (7 get_position = 56 bytes of wire
//                           time per sweep); ratio = rate / floor (higher is better)
//   mega_round_trip_<baud>  ServoPositionRead of seven joints: first request byte sent to
//                           last reply byte received, worst of 200 requests spread over
//                           the poll cycle; limit = its wire time (12 + 26 bytes) / 0.90,
//                           i.e. wire time / round trip >= 0.90 (lower ratio is better)
#include <algorithm>
#include <cstdio>
#include <vector>

#include "devices/joint_avr/avr_mega_arm.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "elf_sizes.hpp"

namespace {

using namespace armctl;

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

joint_avr::AvrMegaArm make_arm(std::uint32_t baud) {
  joint_sim::ArmConfig config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  config.baud = baud;
  const std::string elf =
      baud == 115200 ? joint_avr::mega_firmware_elf_115200() : joint_avr::default_mega_firmware_elf();
  return joint_avr::AvrMegaArm(std::move(config), elf, baud);
}

int bench_baud(std::uint32_t baud) {
  joint_avr::AvrMegaArm arm = make_arm(baud);
  arm.advance(std::chrono::milliseconds(500));  // start-up commands done, polling
  // Refresh: every transaction while idle is a get_position (two select edges each).
  const auto edges0 = arm.select_edges();
  const TimePoint t0 = arm.now();
  arm.advance(std::chrono::seconds(3));
  const double sweeps = double(arm.select_edges() - edges0) / 2.0 / 7.0;
  const double rate = sweeps / seconds(arm.now() - t0);
  const double floor_rate = 1.0 / seconds(wire_time(8 * 7, baud));
  std::printf("BENCH mega_refresh_%u %.3f sweeps/s limit %.3f ratio %.3f\n", baud, rate, floor_rate,
              rate / floor_rate);

  const std::vector<std::uint8_t> request{0x55, 0x55, 0x0A, 0x15, 0x07, 1, 2, 3, 4, 5, 6, 7};
  const std::size_t reply_bytes = 2 + 1 + 1 + 1 + 3 * 7;
  const Duration wire = wire_time(request.size() + reply_bytes, baud);
  Duration worst{};
  int lost = 0;
  for (int i = 0; i < 200; ++i) {
    arm.advance(std::chrono::microseconds(2000 + (i * 7919) % 9000));  // spread over the poll cycle
    arm.take_upstream();
    const TimePoint sent = arm.now();
    arm.send_upstream(request);
    std::size_t got = 0;
    TimePoint last{};
    while (got < reply_bytes && arm.now() - sent < std::chrono::milliseconds(500)) {
      arm.advance(std::chrono::microseconds(100));
      for (const auto& b : arm.take_upstream()) {
        ++got;
        last = b.at;
      }
    }
    if (got < reply_bytes) {
      ++lost;
      continue;
    }
    worst = std::max(worst, last - sent);
  }
  std::printf("# mega_round_trip_%u: worst %.2f ms, wire time %.2f ms, %d of 200 unanswered\n", baud,
              seconds(worst) * 1e3, seconds(wire) * 1e3, lost);
  const double limit_ms = seconds(wire) * 1e3 / 0.9;
  std::printf("BENCH mega_round_trip_%u %.3f ms limit %.3f ratio %.3f\n", baud, seconds(worst) * 1e3, limit_ms,
              seconds(worst) * 1e3 / limit_ms);
  return lost;
}

}  // namespace

int main() {
  const std::string elf = joint_avr::default_mega_firmware_elf();
  const bench::Sizes sizes = bench::elf_sizes(elf);
  if (!sizes.ok) {
    std::fprintf(stderr, "bench_mega_controller: cannot read sizes of %s with avr-size\n", elf.c_str());
    return 1;
  }
  bench::bench_line("mega_flash", double(sizes.text + sizes.data), "bytes", 65536);
  bench::bench_line("mega_static_ram", double(sizes.data + sizes.bss + sizes.noinit), "bytes", 4096);
  int lost = 0;
  for (const std::uint32_t baud : {9600u, 115200u}) lost += bench_baud(baud);
  return lost == 0 ? 0 : 1;
}

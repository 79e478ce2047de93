// Firmware budgets: flash and static RAM from the ELF (avr-size), and worst-case cycle
// counts measured on emulated silicon (libsimavr) while all seven joints run step moves at
// 115200 baud with bus traffic, once with config/scara.arm.json's tuning in EEPROM and once
// with the default tuning a board gets from `make flash`. One line per figure:
//   BENCH <name> <value> <unit> limit <L> ratio <value/L>   (lower ratio is better)
// Cycle counts: from the interrupt's dispatch to the end of its RETI as simavr counts
// cycles, plus the 4-cycle hardware interrupt response simavr leaves out. The control tick
// runs with interrupts enabled; its figure is its own cycles (time spent in encoder/UART
// ISRs that nested inside it is subtracted and printed separately on the "# also" line).
#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include "devices/joint_avr/atmega328p.hpp"
#include "devices/joint_avr/avr_arm.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "elf_sizes.hpp"

namespace {

using namespace armctl;
namespace m = joint_avr::atmega328p;

struct Figures {
  std::uint64_t tick = 0, tick_gross = 0, encoder = 0, turnaround = 0, rx_isr = 0, select_isr = 0, edges = 0;
  std::uint64_t contentions = 0;
  int failures = 0;            // failed transactions, and joints faulted (or unread) at the end
  std::string faulted_joints;  // " 2 5"
};

Figures run_arm(bool scara_tuning) {
  joint_sim::ArmConfig config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  config.baud = 115200;
  joint_avr::AvrArmOptions options;
  options.write_tuning = scara_tuning;
  joint_avr::AvrArm arm(config, options);
  arm.advance(std::chrono::milliseconds(20));
  joint_bus::BusMaster master(arm.link());
  Figures f;
  // Six back-and-forth step moves on every joint at once, with pings and position reads in
  // between: encoder edges at full speed, control ticks under load, bus replies.
  for (int round = 0; round < 6; ++round) {
    const std::int16_t target = round % 2 == 0 ? 3000 : -1000;
    for (int j = 1; j <= 7; ++j) f.failures += master.drive_to(j, target).ok() ? 0 : 1;
    for (int step = 0; step < 40; ++step) {
      for (int j = 1; j <= 7; ++j) {
        f.failures += master.ping(j, static_cast<std::int16_t>(step * 7 + j)).ok() ? 0 : 1;
        f.failures += master.get_position(j).ok() ? 0 : 1;
      }
      arm.advance(std::chrono::milliseconds(10));
    }
  }
  for (int j = 1; j <= 7; ++j) {
    const joint_avr::AvrJoint& joint = arm.joint(j);
    const joint_avr::AvrChip& chip = joint.chip();
    f.tick = std::max(f.tick, chip.isr_stats(m::vector_timer0_compa).max_own_cycles);
    f.tick_gross = std::max(f.tick_gross, chip.isr_stats(m::vector_timer0_compa).max_cycles);
    f.encoder = std::max({f.encoder, chip.isr_stats(m::vector_int0).max_cycles,
                          chip.isr_stats(m::vector_int1).max_cycles});
    f.edges += chip.isr_stats(m::vector_int0).count + chip.isr_stats(m::vector_int1).count;
    f.rx_isr = std::max(f.rx_isr, chip.isr_stats(m::vector_usart_rx).max_cycles);
    f.select_isr = std::max(f.select_isr, chip.isr_stats(m::vector_pcint0).max_cycles);
    f.turnaround = std::max(f.turnaround, joint.rx_to_tx().max_cycles);
    // A run that faulted would not measure the loop: every joint must have followed.
    auto d = master.read_diagnostics(j);
    if (!d.ok() || d.value().faults != 0) {
      ++f.failures;
      f.faulted_joints += " " + std::to_string(j);
    }
  }
  f.contentions = arm.bus().stats().contentions;
  return f;
}

}  // namespace

int main() {
  const std::string elf = joint_avr::default_firmware_elf();
  const bench::Sizes sizes = bench::elf_sizes(elf);
  if (!sizes.ok) {
    std::fprintf(stderr, "bench_firmware: cannot read sizes of %s with avr-size\n", elf.c_str());
    return 1;
  }
  bench::bench_line("fw_flash", double(sizes.text + sizes.data), "bytes", 8192);
  bench::bench_line("fw_static_ram", double(sizes.data + sizes.bss + sizes.noinit), "bytes", 512);

  // Twice: with config/scara.arm.json's tuning in every joint's EEPROM, and with none (the
  // portable default_tuning(), what a board gets from `make flash`).
  int failures = 0;
  for (const bool scara_tuning : {true, false}) {
    const Figures f = run_arm(scara_tuning);
    failures += f.failures;
    if (f.failures != 0)
      std::fprintf(stderr,
                   "bench_firmware: with %s, %d transactions failed or joints ended faulted (joints:%s): "
                   "the figures of this run were measured on an arm that did not follow its moves\n",
                   scara_tuning ? "config/scara.arm.json's tuning" : "the default tuning", f.failures,
                   f.faulted_joints.empty() ? " none" : f.faulted_joints.c_str());
    const char* suffix = scara_tuning ? "" : "_default_tuning";
    const std::string tick_name = std::string("fw_control_tick_worst") + suffix;
    bench::bench_line(tick_name.c_str(), double(f.tick), "cycles", 1600);
    if (!scara_tuning) continue;
    // One word (2 bytes of 10 bits) at 115200 baud, in CPU cycles at 16 MHz.
    const double word_cycles = 20.0 * m::clock_hz / 115200.0;
    bench::bench_line("fw_encoder_isr_worst", double(f.encoder), "cycles", 100);
    bench::bench_line("fw_turnaround_worst", double(f.turnaround), "cycles", word_cycles);
    std::printf("# also: control tick with nested ISRs %llu cycles, uart rx isr %llu cycles, "
                "select isr %llu cycles, %llu encoder edges, %d failed transactions, %llu bus "
                "contentions\n",
                (unsigned long long)f.tick_gross, (unsigned long long)f.rx_isr, (unsigned long long)f.select_isr,
                (unsigned long long)f.edges, f.failures, (unsigned long long)f.contentions);
  }
  return failures == 0 ? 0 : 1;
}

// The whole SCARA on emulated silicon: the Mega controller firmware on an emulated
// ATmega2560 wired to an AvrArm (seven emulated ATmega328P joints running the joint
// firmware, with their motors) over the simulated joint bus: UART1 to the bus, PA0..PA6
// (D22..D28) to the select lines. UART0 — Robot Commands upstream — is reached through
// send_upstream()/take_upstream() with wire timing. Test tool only (libsimavr is GPL).
//
// Coupling, in steps of simulated time: the Mega runs to the end of the step while its
// select edges and bus bytes are recorded with their cycle; they are then applied to the
// bus at those instants, the bus and the joints run to the end of the step, and the bytes
// the bus delivered to the master are handed to the Mega's UART1. Steps are short (a
// quarter of a byte time) while a joint is selected or bytes are on the wire, longer while
// the bus is idle, and a step ends when a joint's byte on the wire ends: a byte from the
// joints reaches the Mega's UART1 when its stop bit ends, as on the real bus.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "devices/joint_avr/avr_arm.hpp"

namespace armctl::joint_avr {

// The Mega controller ELF this build produced (ARMCTL_MEGA_FIRMWARE_ELF; 9600 baud both
// sides) and the one built for 115200 upstream and on the bus.
std::string default_mega_firmware_elf();
std::string mega_firmware_elf_115200();
// 9600 baud both sides, the battery measured on A0 through the 47k/10k divider
// (ARMCTL_BATTERY_ADC=1): feed it with mega().set_adc_millivolts(0, ...).
std::string mega_firmware_elf_battery();

struct UpstreamByte {
  std::uint8_t value;
  TimePoint at;  // its stop bit ended (the host has it)
};

// One thing on the joint bus, for timing it (bench_mega_controller's turnarounds).
struct BusTraceEvent {
  enum class Kind : std::uint8_t {
    select_rise,
    select_fall,
    master_byte,  // the Mega wrote a byte to UART1 (it starts then if the UART was idle)
    joint_byte,   // a joint's byte reached the Mega (its stop bit ended)
  };
  Kind kind;
  int joint;  // 1..7 for select edges, 0 for bytes
  TimePoint at;
};

class AvrMegaArm {
 public:
  // config.baud must be the joint bus baud the Mega ELF was built for; upstream_baud the
  // Robot Commands one.
  AvrMegaArm(joint_sim::ArmConfig config, std::string mega_elf, std::uint32_t upstream_baud,
             AvrArmOptions joints = {});

  TimePoint now() const { return arm_.now(); }
  void run_until(TimePoint t);
  void advance(Duration d) { run_until(now() + d); }

  // Bytes from the host: they go out back to back from now (or after the ones before).
  void send_upstream(std::span<const std::uint8_t> bytes);
  // Bytes the Mega sent upstream that have fully arrived by now.
  std::vector<UpstreamByte> take_upstream();
  std::uint32_t upstream_baud() const { return upstream_baud_; }

  AvrArm& arm() { return arm_; }
  AvrChip& mega() { return *mega_; }
  // A reset pulse on the Mega (its watchdog, or DTR when a host opens the USB port): every
  // pin becomes a high-Z input, and the joint boards' pull-downs take the select lines LOW.
  void reset_mega();
  std::uint64_t select_edges() const { return select_edges_; }
  // Every select edge and bus byte from now on, in order; empty: none.
  void set_bus_trace(std::function<void(const BusTraceEvent&)> trace) { trace_ = std::move(trace); }

 private:
  struct BusEvent {
    std::uint64_t cycle;
    int joint;       // 0: a byte
    bool level;
    std::uint8_t byte;
  };
  std::uint64_t cycle_at(TimePoint t) const;
  TimePoint time_at(std::uint64_t cycle) const;
  void step(TimePoint end);
  bool bus_active();

  AvrArm arm_;
  std::unique_ptr<AvrChip> mega_;
  std::uint32_t upstream_baud_;
  TimePoint start_;
  Duration upstream_byte_time_;
  Duration short_step_;
  std::vector<BusEvent> events_;
  std::deque<UpstreamByte> to_mega_;    // `at` = when it has arrived at the Mega
  TimePoint upstream_free_at_{};
  std::deque<UpstreamByte> from_mega_;  // `at` = when the host has it
  TimePoint from_mega_free_at_{};
  TimePoint last_bus_activity_{};
  std::uint8_t selects_ = 0;
  std::uint64_t select_edges_ = 0;
  std::function<void(const BusTraceEvent&)> trace_;
};

}  // namespace armctl::joint_avr

// What a joint reports about itself (read_diagnostic, code 40): its held faults and the
// counters its firmware keeps. Word layout: portable/joint_bus_codes.hpp (diagnostic_*),
// docs/joint-controller.md "Faults and diagnostics".
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "portable/joint_bus_codes.hpp"

namespace armctl::joint_bus {

struct JointDiagnostics {
  std::uint16_t faults = 0;  // fault_* bits; any of them keeps the bridge off
  std::uint16_t bus_events_lost = 0;
  std::uint16_t encoder_edges_lost = 0;
  std::uint16_t uart_errors = 0;
  std::uint16_t reset_cause = 0;  // MCUSR bits: 1 power-on, 2 external, 4 brown-out, 8 watchdog
  std::uint16_t abandoned_transactions = 0;
  std::uint16_t settings = 0;  // setting_* bits

  bool runaway() const { return (faults & fault_runaway) != 0; }
  bool following_error() const { return (faults & fault_following_error) != 0; }
  bool motor_reversed() const { return (settings & setting_motor_reversed) != 0; }
  bool legacy_master() const { return (settings & setting_legacy_master) != 0; }
};

JointDiagnostics diagnostics_from_words(const std::array<std::uint16_t, diagnostic_count>& words);

// "runaway, following error" / "none"; unknown bits as "bit N".
std::string describe_faults(std::uint16_t faults);
// "power-on", "watchdog", "external, brown-out"; "unknown (0)" for 0.
std::string describe_reset_cause(std::uint16_t cause);
// One line for people: faults, then every counter, reset cause and settings.
std::string describe(const JointDiagnostics& d);

}  // namespace armctl::joint_bus

#include "devices/joint_bus/joint_diagnostics.hpp"

#include <fmt/core.h>

namespace armctl::joint_bus {

JointDiagnostics diagnostics_from_words(const std::array<std::uint16_t, diagnostic_count>& w) {
  JointDiagnostics d;
  d.faults = w[diagnostic_faults];
  d.bus_events_lost = w[diagnostic_bus_events_lost];
  d.encoder_edges_lost = w[diagnostic_encoder_edges_lost];
  d.uart_errors = w[diagnostic_uart_errors];
  d.reset_cause = w[diagnostic_reset_cause];
  d.abandoned_transactions = w[diagnostic_abandoned];
  d.settings = w[diagnostic_settings];
  return d;
}

namespace {
std::string join_bits(std::uint16_t bits, const char* const names[], int named) {
  std::string out;
  for (int b = 0; b < 16; ++b) {
    if ((bits & (1u << b)) == 0) continue;
    if (!out.empty()) out += ", ";
    out += b < named ? std::string(names[b]) : fmt::format("bit {}", b);
  }
  return out;
}
}  // namespace

std::string describe_faults(std::uint16_t faults) {
  static const char* const names[] = {"runaway", "following error"};
  return faults == 0 ? std::string("none") : join_bits(faults, names, 2);
}

std::string describe_reset_cause(std::uint16_t cause) {
  static const char* const names[] = {"power-on", "external", "brown-out", "watchdog"};
  return cause == 0 ? std::string("unknown (0)") : join_bits(cause, names, 4);
}

std::string describe(const JointDiagnostics& d) {
  return fmt::format(
      "faults: {}{}; lost bus events {}, lost encoder edges {}, UART errors {}, abandoned "
      "transactions {}; last reset: {}; motor polarity {}, {} master",
      describe_faults(d.faults), d.faults != 0 ? " (bridge off until clear-faults)" : "", d.bus_events_lost,
      d.encoder_edges_lost, d.uart_errors, d.abandoned_transactions, describe_reset_cause(d.reset_cause),
      d.motor_reversed() ? "reversed" : "original", d.legacy_master() ? "legacy" : "standard");
}

}  // namespace armctl::joint_bus

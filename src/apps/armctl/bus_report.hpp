// How `armctl bus` shows results: one line per joint for people, or one JSON document.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "devices/joint_bus/bus_failure.hpp"

namespace armctl::cli {

struct BusRow {
  int joint = 0;
  std::optional<Error> error;                      // a failed transaction (JointFailure detail)
  std::optional<std::string> problem;              // a failure that is no transaction's (wait timeout)
  nlohmann::json value;                            // null for commands without a value
  std::string text;                                // the value for people ("position 1200")
};

struct BusReport {
  std::string command;  // the CLI command, e.g. "position"
  std::string device;   // describe(uri)
  std::vector<BusRow> rows;
  nlohmann::json extra = nlohmann::json::object();  // command-specific fields (wait: elapsed)

  int failures() const;
};

inline bool failed(const BusRow& r) { return r.error.has_value() || r.problem.has_value(); }

// Prints the report to stdout (human lines or JSON).
void print_report(const BusReport& report, bool json);

}  // namespace armctl::cli

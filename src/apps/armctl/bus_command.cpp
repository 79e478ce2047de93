// armctl bus [--device URI] [--json] [--retries N] [--verify] COMMAND [JOINT|all] [VALUE]
// The joint bus master from the command line: one command to one joint or to all joints.
#include <chrono>
#include <cmath>
#include <charconv>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "apps/armctl/bus_report.hpp"
#include "apps/armctl/commands.hpp"
#include "apps/armctl/number_options.hpp"
#include "core/error.hpp"
#include "devices/device_registry/device_registry.hpp"
#include "devices/joint_bus/arrival.hpp"
#include "devices/joint_bus/bus_connection.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_bus/device_uri.hpp"

namespace armctl::cli {

namespace {

using joint_bus::BusMaster;

struct BusArgs {
  std::string device = "sim";
  bool json = false;
  int retries = 0;
  bool verify = false;
  std::string joint = "all";
  std::string value;
  bool value_given = false;  // VALUE typed, even empty ('' is refused, not the default)
  double wait_timeout_s = 30.0;
};

[[noreturn]] void usage_error(const std::string& message) {
  throw ArmctlError(ErrorKind::invalid_argument, message);
}

// `what` names the argument as the usage line does (JOINT or VALUE).
long parse_integer(const std::string& command, const char* what, const std::string& text, long lo,
                   long hi, const std::string& meaning) {
  long v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size() || v < lo || v > hi) {
    usage_error(fmt::format("{}: {} '{}' is not allowed: {} is a whole number {}..{}", command, what,
                            text, meaning, lo, hi));
  }
  return v;
}

// JOINT as typed: "all" or 1..7; checked against the bus's own joint count once it is open.
std::vector<int> parse_joints(const std::string& command, const std::string& text, int joint_count) {
  if (text == "all") {
    std::vector<int> all;
    for (int j = 1; j <= joint_count; ++j) all.push_back(j);
    return all;
  }
  const long j = parse_integer(command, "JOINT", text, 1, 7, "a joint (or 'all')");
  if (j > joint_count) {
    usage_error(fmt::format("{}: joint {} is not on this bus: joints are 1..{} (or 'all')", command, j,
                            joint_count));
  }
  return {static_cast<int>(j)};
}

nlohmann::json diagnostics_json(const joint_bus::JointDiagnostics& d) {
  nlohmann::json faults = nlohmann::json::array();
  if (d.runaway()) faults.push_back("runaway");
  if (d.following_error()) faults.push_back("following_error");
  return {{"faults", faults},
          {"fault_bits", d.faults},
          {"bus_events_lost", d.bus_events_lost},
          {"encoder_edges_lost", d.encoder_edges_lost},
          {"uart_errors", d.uart_errors},
          {"abandoned_transactions", d.abandoned_transactions},
          {"reset_cause", joint_bus::describe_reset_cause(d.reset_cause)},
          {"reset_cause_bits", d.reset_cause},
          {"motor_polarity", d.motor_reversed() ? "reversed" : "original"},
          {"master", d.legacy_master() ? "legacy" : "standard"}};
}

template <typename T>
BusRow row_from(int joint, const Result<T>& r, const std::function<void(BusRow&, const T&)>& fill) {
  BusRow row;
  row.joint = joint;
  if (!r.ok()) {
    row.error = r.error();
  } else if (fill) {
    fill(row, r.value());
  }
  return row;
}

// One command of the bus: how it reads VALUE and what it does to one joint.
struct BusCommandSpec {
  std::string name;
  std::string help;
  std::string value_help;  // empty: takes no VALUE
  bool value_optional = false;
};

class BusRunner {
 public:
  explicit BusRunner(const BusArgs& args) : args_(args) {
    connection_ = devices::open_joint_bus(args.device).value();  // value(): the error for main()
    joint_bus::MasterOptions options = connection_->default_options();
    options.retries = args.retries;
    options.verify = args.verify;
    master_ = std::make_unique<BusMaster>(connection_->link(), options);
  }

  BusReport run(const std::string& command) {
    BusReport report;
    report.command = command;
    report.device = connection_->description();
    const std::vector<int> joints = parse_joints(command, args_.joint, master_->joint_count());
    BusMaster& m = *master_;
    const auto dialect = m.options().dialect;

    auto each = [&](const std::function<BusRow(int)>& op) {
      for (int j : joints) report.rows.push_back(op(j));
    };
    auto done = [](BusRow&, const Ok&) {};
    auto as_value = [](const char* what) {
      return [what](BusRow& row, const std::int16_t& v) {
        row.value = v;
        row.text = fmt::format("{} {}", what, v);
      };
    };

    if (command == "ping") {
      const auto v = static_cast<std::int16_t>(
          !args_.value_given ? 1234 : parse_integer(command, "VALUE", args_.value, -32768, 32767, "the ping value"));
      each([&](int j) {
        return row_from<std::int16_t>(j, m.ping(j, v), [](BusRow& row, const std::int16_t& echo) {
          row.value = echo;
          row.text = fmt::format("answered, echo {}", echo);
        });
      });
    } else if (command == "home") {
      each([&](int j) { return row_from<Ok>(j, m.home(j), [](BusRow& r, const auto&) { r.text = "homed (position 0, target 0)"; }); });
    } else if (command == "pid") {
      if (args_.value != "on" && args_.value != "off") {
        usage_error(fmt::format("pid: VALUE '{}' is not allowed: use on or off", args_.value));
      }
      const bool on = args_.value == "on";
      each([&](int j) {
        return row_from<Ok>(j, m.set_pid_state(j, on), [on](BusRow& r, const auto&) {
          r.value = on;
          r.text = on ? "position loop on" : "position loop off";
        });
      });
    } else if (command == "position") {
      each([&](int j) { return row_from<std::int16_t>(j, m.get_position(j), as_value("position")); });
    } else if (command == "target") {
      each([&](int j) { return row_from<std::int16_t>(j, m.get_target(j), as_value("target")); });
    } else if (command == "number") {
      each([&](int j) { return row_from<std::int16_t>(j, m.get_joint_number(j), as_value("joint number")); });
    } else if (command == "drive-dist" || command == "drive-dist-max" || command == "drive-to") {
      const auto kind = command == "drive-to"         ? joint_bus::Drive::to
                        : command == "drive-dist-max" ? joint_bus::Drive::dist_max
                                                      : joint_bus::Drive::dist;
      const auto v = static_cast<std::int16_t>(parse_integer(command, "VALUE", args_.value, -32768, 32767, command == "drive-to" ? "a position in clicks" : "a distance in clicks"));
      if (args_.joint == "all") {
        // All joints told back to back so they start together.
        const std::vector<std::int16_t> values(static_cast<std::size_t>(m.joint_count()), v);
        for (auto& o : m.drive_all(kind, values)) {
          report.rows.push_back(row_from<Ok>(o.joint, o.result, done));
        }
      } else {
        each([&](int j) { return row_from<Ok>(j, m.drive(kind, j, v), done); });
      }
      for (auto& r : report.rows) {
        if (!failed(r)) r.text = fmt::format("{} {} sent", command, v);
      }
    } else if (command == "speed") {
      const int max = joint_bus::max_speed_value(dialect);
      const auto v = static_cast<std::int16_t>(parse_integer(command, "VALUE", args_.value, 0, max,
          dialect == joint_bus::Dialect::legacy ? "the legacy PWM cap" : "the speed limit in percent"));
      each([&](int j) { return row_from<Ok>(j, m.set_speed(j, v), [v](BusRow& r, const auto&) { r.value = v; r.text = fmt::format("speed {}", v); }); });
    } else if (command == "zone") {
      const auto v = static_cast<std::int16_t>(parse_integer(command, "VALUE", args_.value, 0, 32767, "the zone in clicks"));
      each([&](int j) { return row_from<Ok>(j, m.set_zone(j, v), [v](BusRow& r, const auto&) { r.value = v; r.text = fmt::format("zone {}", v); }); });
    } else if (command == "reached") {
      each([&](int j) {
        return row_from<bool>(j, m.check_target_reached(j), [](BusRow& r, const bool& yes) {
          r.value = yes;
          r.text = yes ? "target reached" : "moving (not in zone yet)";
        });
      });
    } else if (command == "wait") {
      wait(joints, report);
    } else if (command == "faults") {
      each([&](int j) {
        return row_from<joint_bus::JointDiagnostics>(j, m.read_diagnostics(j), [](BusRow& r, const joint_bus::JointDiagnostics& d) {
          r.value = diagnostics_json(d);
          r.text = joint_bus::describe(d);
        });
      });
    } else if (command == "clear-faults") {
      each([&](int j) {
        return row_from<Ok>(j, m.clear_faults(j), [](BusRow& r, const auto&) {
          r.text = "faults cleared (holding where it is, bridge on if the loop is on)";
        });
      });
    }
    return report;
  }

 private:
  // Closed loop, in the library: polls until every selected joint is in its zone.
  void wait(const std::vector<int>& joints, BusReport& report) {
    BusMaster& m = *master_;
    const TimePoint start = m.clock().now();
    const auto timeout =
        std::chrono::duration_cast<Duration>(std::chrono::duration<double>(args_.wait_timeout_s));
    for (const auto& a : joint_bus::wait_until_reached(m, joints, start + timeout)) {
      BusRow row;
      row.joint = a.joint;
      if (a.arrived) {
        const double s = std::chrono::duration<double>(a.after).count();
        row.value = s;
        row.text = fmt::format("reached after {:.2f} s", s);
      } else if (joint_bus::joint_failure(*a.error)) {
        row.error = *a.error;  // its polls failed
      } else {
        row.problem = a.error->message;  // still not in its zone at the deadline
      }
      report.rows.push_back(std::move(row));
    }
    report.extra["elapsed_s"] = std::chrono::duration<double>(m.clock().now() - start).count();
  }

  BusArgs args_;
  std::unique_ptr<joint_bus::BusConnection> connection_;
  std::unique_ptr<BusMaster> master_;
};

void run_bus(const BusArgs& args, const std::string& command) {
  BusRunner runner(args);
  const BusReport report = runner.run(command);
  print_report(report, args.json);
  if (const int n = report.failures()) {
    throw ArmctlError(ErrorKind::device, fmt::format("{} of {} joints failed ({})", n, report.rows.size(), command));
  }
}

}  // namespace

void add_bus_command(CLI::App& app) {
  auto args = std::make_shared<BusArgs>();
  CLI::App* bus = app.add_subcommand("bus", "Joint bus master: talk to the SCARA arm's joint controllers");
  bus->require_subcommand(1);
  bus->fallthrough();
  bus->add_option("--device", args->device,
                  "Where the bus is: sim[?baud=N&config=FILE&dead=J,...] (embedded simulated arm, default), unix:/path (armctl sim scara), "
                  "serial:/dev/ttyAMA0?select=17,27,22,5,6,13,19[&baud=115200][&chip=gpiochip0][&dialect=legacy]");
  bus->add_flag("--json", args->json, "Print one JSON document instead of lines");
  bus->add_option("--retries", args->retries, "Extra attempts where repeating is safe (never a sent relative move)")
      ->check(whole_number_in(0, 10));
  bus->add_flag("--verify", args->verify, "Follow each drive command with get_target and report a mismatch");

  const std::vector<BusCommandSpec> specs = {
      {"ping", "Ping joints (the joint echoes VALUE, default 1234)", "value to echo (-32768..32767)", true},
      {"home", "Set position and target to 0 (loop state unchanged)", "", false},
      {"pid", "Position loop on or off", "on | off", false},
      {"position", "Read positions (clicks)", "", false},
      {"target", "Read targets (clicks)", "", false},
      {"number", "Read each joint's own joint number", "", false},
      {"drive-dist", "Move the target by VALUE clicks", "distance in clicks (-32768..32767)", false},
      {"drive-dist-max", "Set target to position + VALUE clicks", "distance in clicks (-32768..32767)", false},
      {"drive-to", "Set target to VALUE clicks", "position in clicks (-32768..32767)", false},
      {"speed", "Speed limit in % of the joint's maximum", "0..100 (legacy dialect: 0..255)", false},
      {"zone", "Zone in clicks within which the target counts as reached", "0..32767", false},
      {"reached", "Is each joint within its zone of its target?", "", false},
      {"wait", "Poll until every selected joint is within its zone", "", false},
      {"faults", "Read each joint's faults and diagnostic counters (runaway, following error, lost events, reset cause, settings)", "", false},
      {"clear-faults", "Clear each joint's faults: it holds where it is and drives again", "", false},
  };
  for (const auto& spec : specs) {
    CLI::App* sub = bus->add_subcommand(spec.name, spec.help);
    sub->add_option("joint", args->joint, "Joint 1..7 or all (default all)");
    if (!spec.value_help.empty()) {
      auto* opt = sub->add_option("value", args->value, spec.value_help)->each([args](const std::string&) {
        args->value_given = true;
      });
      if (!spec.value_optional) opt->required();
    }
    if (spec.name == "wait") {
      sub->add_option("--timeout", args->wait_timeout_s, "Give up after this many seconds (default 30)")
          ->check(number_in(0, 3600, "s", true));
    }
    const std::string name = spec.name;
    sub->callback([args, name] { run_bus(*args, name); });
  }
}

}  // namespace armctl::cli

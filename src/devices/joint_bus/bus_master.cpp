#include "devices/joint_bus/bus_master.hpp"

#include <algorithm>
#include <array>
#include <chrono>

#include <fmt/core.h>

#include "devices/joint_bus/reconnecting_link.hpp"
#include "portable/joint_bus_codes.hpp"

namespace armctl::joint_bus {

namespace {

bool is_relative_move(std::int16_t command) {
  return command == cmd_drive_dist || command == cmd_drive_dist_max;
}

// Failures after which trying again can help. 930 and 940 are the joint's considered
// answer and would only repeat.
bool retry_can_help(FailureKind kind) {
  return kind == FailureKind::no_answer || kind == FailureKind::wrong_joint ||
         kind == FailureKind::bad_status || kind == FailureKind::ping_bad_echo;
}

double to_ms(Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

}  // namespace

const char* command_name(std::int16_t command) {
  switch (command) {
    case cmd_ping: return "ping";
    case cmd_home: return "home";
    case cmd_set_pid_state: return "set_pid_state";
    case cmd_get_position: return "get_position";
    case cmd_get_target: return "get_target";
    case cmd_get_joint_number: return "get_joint_number";
    case cmd_drive_dist: return "drive_dist";
    case cmd_drive_dist_max: return "drive_dist_max";
    case cmd_drive_to: return "drive_to";
    case cmd_set_speed: return "set_speed";
    case cmd_set_zone: return "set_zone";
    case cmd_check_target_reached: return "check_target_reached";
    case cmd_read_diagnostic: return "read_diagnostic";
    case cmd_clear_faults: return "clear_faults";
    default: return "unknown";
  }
}

BusMaster::BusMaster(transport::JointBusLink& link, MasterOptions options)
    : link_(link), options_(options) {}

Duration BusMaster::word_timeout() const { return options_.timing.word_timeout(link_.baud()); }

Error BusMaster::fail(FailureKind kind, Stage stage, int joint, bool command_sent,
                      std::optional<std::int16_t> status, std::string message) {
  ++counters_.failures;
  return bus_error(JointFailure{kind, stage, joint, status, command_sent, false}, std::move(message));
}

std::optional<std::int16_t> BusMaster::read_word(TimePoint deadline) {
  const std::optional<std::uint8_t> low = link_.read_byte(deadline);
  if (!low) return std::nullopt;
  const std::optional<std::uint8_t> high = link_.read_byte(deadline);
  if (!high) return std::nullopt;
  return word_from(*low, *high);
}

void BusMaster::idle_until(TimePoint until) {
  try {
    while (link_.read_byte(until)) ++counters_.drained_bytes;
  } catch (const ArmctlError&) {
    // A failed link shows in the next transaction's result; idling has none to give.
  }
}

void BusMaster::abandon(int joint) {
  link_.set_select(joint, false);
  settle();
}

void BusMaster::settle() {
  // Whatever is still in flight (a late STATUS, garbage) must not be read as the next
  // transaction's READY: discard until the bus has been quiet for one word timeout, but
  // never longer than a bounded time even if garbage keeps coming.
  const Duration quiet = word_timeout();
  const TimePoint give_up = link_.clock().now() + quiet * 8;
  while (link_.clock().now() < give_up) {
    if (!link_.read_byte(link_.clock().now() + quiet)) break;
    ++counters_.drained_bytes;
  }
}

Result<std::optional<std::int16_t>> BusMaster::attempt(int joint, std::int16_t command,
                                                       std::optional<std::int16_t> data) {
  try {
    return exchange(joint, command, data);
  } catch (const ArmctlError& e) {
    // The link itself failed (a serial port unplugged, a remote simulated arm gone). The
    // COMMAND word may have gone out: say so, so that a relative move is never repeated.
    Error error = fail(FailureKind::link, Stage::ready, joint, true, std::nullopt,
                       fmt::format("joint {}: {} failed on the link: {}", joint,
                                   command_name(command), e.error().message));
    error.kind = e.error().kind;  // io, timeout or protocol, as the link said
    if (e.error().detail_as<LinkLost>()) std::any_cast<JointFailure>(&error.detail)->link_lost = true;
    return error;
  }
}

Result<std::optional<std::int16_t>> BusMaster::exchange(int joint, std::int16_t command,
                                                        std::optional<std::int16_t> data) {
  const char* name = command_name(command);
  if (joint < 1 || joint > joint_count()) {
    return fail(FailureKind::invalid_argument, Stage::before_command, joint, false, std::nullopt,
                fmt::format("joint {} does not exist: joints are 1..{}", joint, joint_count()));
  }
  const CommandShape shape = command_shape(command);
  if (shape.known && shape.takes_data != data.has_value()) {
    return fail(FailureKind::invalid_argument, Stage::before_command, joint, false, std::nullopt,
                fmt::format("{} {} a data word", name, shape.takes_data ? "needs" : "takes no"));
  }
  ++counters_.transactions;
  const double timeout_ms = to_ms(word_timeout());

  counters_.drained_bytes += link_.drain();
  link_.set_select(joint, true);
  const std::optional<std::int16_t> ready = read_word(link_.clock().now() + word_timeout());
  if (!ready) {
    abandon(joint);
    return fail(FailureKind::no_answer, Stage::ready, joint, false, std::nullopt,
                fmt::format("joint {}: no READY within {:.2f} ms ({}, 990)", joint, timeout_ms, name));
  }
  if (*ready != joint) {
    abandon(joint);
    return fail(FailureKind::wrong_joint, Stage::ready, joint, false, std::nullopt,
                fmt::format("joint {}: READY was {} instead of {}; select dropped, {} not sent (910)",
                            joint, *ready, joint, name));
  }

  std::array<std::uint8_t, 4> out{word_low(command), word_high(command), 0, 0};
  std::size_t out_len = 2;
  if (data) {
    out[2] = word_low(*data);
    out[3] = word_high(*data);
    out_len = 4;
  }
  link_.write(std::span<const std::uint8_t>(out.data(), out_len));
  link_.flush();  // every byte on the wire before we wait for RESPONSE or drop select

  std::optional<std::int16_t> response;
  if (shape.returns_value) {
    response = read_word(link_.clock().now() + word_timeout());
    if (!response && command == cmd_read_diagnostic) {
      // A joint running the original firmware sends no RESPONSE to this extension: it
      // waits for select to fall and answers "unknown" (93). Listen for that STATUS so
      // the caller learns why, instead of a bare 990.
      link_.set_select(joint, false);
      const std::optional<std::int16_t> status = read_word(link_.clock().now() + word_timeout());
      settle();
      if (status && interpret_status(options_.dialect, command, *status) == StatusMeaning::unknown_command) {
        return fail(FailureKind::unknown_command, Stage::status, joint, true, status,
                    fmt::format("joint {}: command {} unknown to the joint (STATUS {}, 930)", joint, command,
                                *status));
      }
      return fail(FailureKind::no_answer, Stage::response, joint, true, status,
                  fmt::format("joint {}: no RESPONSE to {} within {:.2f} ms (990)", joint, name, timeout_ms));
    }
    if (!response) {
      abandon(joint);
      return fail(FailureKind::no_answer, Stage::response, joint, true, std::nullopt,
                  fmt::format("joint {}: no RESPONSE to {} within {:.2f} ms (990)", joint, name,
                              timeout_ms));
    }
  }

  link_.set_select(joint, false);
  const std::optional<std::int16_t> status = read_word(link_.clock().now() + word_timeout());
  if (!status) {
    settle();
    return fail(FailureKind::no_answer, Stage::status, joint, true, std::nullopt,
                fmt::format("joint {}: no STATUS after {} within {:.2f} ms (990)", joint, name,
                            timeout_ms));
  }

  switch (interpret_status(options_.dialect, command, *status)) {
    case StatusMeaning::success:
      break;
    case StatusMeaning::unknown_command:
      return fail(FailureKind::unknown_command, Stage::status, joint, true, status,
                  fmt::format("joint {}: command {} unknown to the joint (STATUS {}, 930)", joint,
                              command, *status));
    case StatusMeaning::bad_data:
      return fail(FailureKind::bad_data, Stage::status, joint, true, status,
                  fmt::format("joint {}: {} refused data {} (STATUS {}, 940); nothing changed",
                              joint, name, data ? *data : 0, *status));
    case StatusMeaning::unexpected: {
      settle();
      const std::optional<std::int16_t> success = success_status(options_.dialect, command);
      if (!success) {
        // No code means success for a command the joints do not know (1090 is nothing).
        return fail(FailureKind::bad_status, Stage::status, joint, true, status,
                    fmt::format("joint {}: STATUS {} after command {}, which no joint knows "
                                "(expected the unknown-command answer {})",
                                joint, *status, command,
                                options_.dialect == Dialect::legacy ? legacy_status_unknown_command
                                                                    : std::int16_t{status_unknown_command}));
      }
      return fail(FailureKind::bad_status, Stage::status, joint, true, status,
                  fmt::format("joint {}: STATUS {} is neither success ({}) nor an error code after {}",
                              joint, *status, *success, name));
    }
  }
  if (command == cmd_ping && response != data) {
    return fail(FailureKind::ping_bad_echo, Stage::response, joint, true, status,
                fmt::format("joint {}: ping echoed {} instead of {} (920)", joint,
                            response.value_or(0), data.value_or(0)));
  }
  return response;
}

Result<std::optional<std::int16_t>> BusMaster::transact(int joint, std::int16_t command,
                                                           std::optional<std::int16_t> data) {
  return attempt(joint, command, data);
}

Result<std::optional<std::int16_t>> BusMaster::with_retries(int joint, std::int16_t command,
                                                               std::optional<std::int16_t> data) {
  for (int tries = 0;; ++tries) {
    Result<std::optional<std::int16_t>> r = attempt(joint, command, data);
    if (r.ok()) return r;
    const JointFailure* f = joint_failure(r.error());
    const bool unsafe = is_relative_move(command) && f->command_sent;
    if (tries >= options_.retries || !retry_can_help(f->kind) || unsafe) return r;
    ++counters_.retries;
  }
}

Status BusMaster::command_only(int joint, std::int16_t command,
                                        std::optional<std::int16_t> data) {
  auto r = with_retries(joint, command, data);
  if (!r) return r.error();
  return Ok{};
}

Result<std::int16_t> BusMaster::query(int joint, std::int16_t command) {
  auto r = with_retries(joint, command, std::nullopt);
  if (!r) return r.error();
  return r.value().value();  // every query command returns a RESPONSE word
}

Result<std::int16_t> BusMaster::ping(int joint, std::int16_t value) {
  auto r = with_retries(joint, cmd_ping, value);
  if (!r) return r.error();
  return r.value().value();
}

Status BusMaster::home(int joint) { return command_only(joint, cmd_home, std::nullopt); }
Status BusMaster::set_pid_state(int joint, bool on) {
  return command_only(joint, cmd_set_pid_state, static_cast<std::int16_t>(on ? 1 : 0));
}
Result<std::int16_t> BusMaster::get_position(int joint) { return query(joint, cmd_get_position); }
Result<std::int16_t> BusMaster::get_target(int joint) { return query(joint, cmd_get_target); }
Result<std::int16_t> BusMaster::get_joint_number(int joint) {
  return query(joint, cmd_get_joint_number);
}
Status BusMaster::set_speed(int joint, std::int16_t speed) {
  return command_only(joint, cmd_set_speed, speed);
}
Status BusMaster::set_zone(int joint, std::int16_t zone) {
  return command_only(joint, cmd_set_zone, zone);
}
Result<bool> BusMaster::check_target_reached(int joint) {
  auto r = query(joint, cmd_check_target_reached);
  if (!r) return r.error();
  if (*r != 0 && *r != 1) {
    return fail(FailureKind::bad_status, Stage::response, joint, true, std::nullopt,
                fmt::format("joint {}: check_target_reached answered {} (allowed: 0 or 1)", joint,
                            *r));
  }
  return *r == 1;
}

Result<std::int16_t> BusMaster::read_diagnostic(int joint, std::int16_t index) {
  auto r = with_retries(joint, cmd_read_diagnostic, index);
  if (!r) return r.error();
  return r.value().value();
}

Status BusMaster::clear_faults(int joint) { return command_only(joint, cmd_clear_faults, std::nullopt); }

Result<JointDiagnostics> BusMaster::read_diagnostics(int joint) {
  std::array<std::uint16_t, diagnostic_count> words{};
  for (std::int16_t i = 0; i < diagnostic_count; ++i) {
    auto w = read_diagnostic(joint, i);
    if (!w) {
      Error e = w.error();
      const JointFailure* f = joint_failure(e);
      if (f != nullptr && f->kind == FailureKind::unknown_command) {
        e.message = fmt::format("joint {}: no fault reading: its firmware does not know read_diagnostic "
                                "(the original firmware? STATUS {})",
                                joint, f->status_word.value_or(0));
      }
      return e;
    }
    words[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(*w);
  }
  return diagnostics_from_words(words);
}

Status BusMaster::drive_dist(int joint, std::int16_t d) { return drive(Drive::dist, joint, d); }
Status BusMaster::drive_dist_max(int joint, std::int16_t d) {
  return drive(Drive::dist_max, joint, d);
}
Status BusMaster::drive_to(int joint, std::int16_t p) { return drive(Drive::to, joint, p); }

Result<BusMaster::Reading> BusMaster::read_before_drive(Drive kind, int joint) {
  Reading before;
  if (kind == Drive::dist) {
    auto t = get_target(joint);
    if (!t) return t.error();
    before.target_before = *t;
  } else if (kind == Drive::dist_max) {
    auto p = get_position(joint);
    if (!p) return p.error();
    before.position_before = *p;
  }
  return before;
}

Status BusMaster::verify_drive(Drive kind, int joint, std::int16_t value,
                                        const Reading& before) {
  const char* name = command_name(static_cast<std::int16_t>(kind));
  auto unverified = [&](const Error& e) {
    JointFailure f = *joint_failure(e);
    f.stage = Stage::verify;
    f.command_sent = true;
    return bus_error(f, fmt::format("joint {}: {} {} was accepted but could not be verified: {}",
                                    joint, name, value, e.message));
  };
  auto target = get_target(joint);
  if (!target) return unverified(target.error());
  const int t = *target;
  bool matches = false;
  std::string expected;
  if (kind == Drive::to) {
    matches = t == value;
    expected = fmt::format("{}", value);
  } else if (kind == Drive::dist) {
    const int want = *before.target_before + value;
    matches = t == want;
    expected = fmt::format("{} ({} + {})", want, *before.target_before, value);
  } else {
    auto after = get_position(joint);
    if (!after) return unverified(after.error());
    const int tol = options_.verify_position_tolerance;
    const int lo = std::min<int>(*before.position_before, *after) - tol;
    const int hi = std::max<int>(*before.position_before, *after) + tol;
    matches = t - value >= lo && t - value <= hi;
    expected = fmt::format("position {}..{} + {}", lo, hi, value);
  }
  if (matches) return Ok{};
  return fail(FailureKind::verify_mismatch, Stage::verify, joint, true, std::nullopt,
              fmt::format("joint {}: target is {} after {} {}, expected {}; not corrected "
                          "(a second move could make it worse)",
                          joint, t, name, value, expected));
}

Status BusMaster::drive(Drive kind, int joint, std::int16_t value) {
  const auto command = static_cast<std::int16_t>(kind);
  Reading before;
  if (options_.verify) {
    auto b = read_before_drive(kind, joint);
    if (!b) return b.error();  // command_sent stays false: the drive never went out
    before = *b;
  }
  auto r = command_only(joint, command, value);
  if (!r || !options_.verify) return r;
  return verify_drive(kind, joint, value, before);
}

PerJoint<Ok> BusMaster::drive_all(Drive kind, std::span<const std::int16_t> values) {
  const auto n = static_cast<std::size_t>(joint_count());
  PerJoint<Ok> out;
  out.reserve(n);
  if (values.size() != n) {
    for (int j = 1; j <= joint_count(); ++j) {
      out.push_back({j, bus_error(JointFailure{FailureKind::invalid_argument, Stage::before_command,
                                               j, std::nullopt, false, false},
                                  fmt::format("{} values given for {} joints", values.size(), n))});
    }
    return out;
  }
  std::vector<std::optional<Reading>> before(n);
  const auto command = static_cast<std::int16_t>(kind);
  for (int j = 1; j <= joint_count(); ++j) {
    const auto i = static_cast<std::size_t>(j - 1);
    if (options_.verify) {
      auto b = read_before_drive(kind, j);
      if (!b) {
        out.push_back({j, b.error()});
        continue;
      }
      before[i] = *b;
    }
    out.push_back({j, command_only(j, command, values[i])});
  }
  if (options_.verify) {
    for (auto& o : out) {
      const auto i = static_cast<std::size_t>(o.joint - 1);
      if (o.result.ok()) o.result = verify_drive(kind, o.joint, values[i], *before[i]);
    }
  }
  return out;
}

}  // namespace armctl::joint_bus

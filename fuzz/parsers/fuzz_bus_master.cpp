// The joint-bus master (devices/joint_bus/bus_master.hpp) against joints that send
// arbitrary bytes. Input: a header (joints, baud, dialect, retries, verify), then
// operations, each  OP JOINT VALUE_LO VALUE_HI CHUNK_LEN DELAY  followed by CHUNK_LEN bytes
// that the joints send during it (fuzz_link.hpp). Checked after every operation:
//  - a success was built from bytes the joints really sent in that transaction, in the
//    spec's order: READY = the joint's number, the RESPONSE returned, the command's
//    success STATUS (computed here from the spec, not with the master's helpers);
//  - ping succeeds only with its echo; drive_to with verify only when the target read back
//    equals the value; check_target_reached only with 0 or 1;
//  - a joint that does not exist fails with invalid_argument and nothing on the bus;
//  - no select line is left high, never two at once, no bytes without a selected joint;
//  - the operation ends within a bounded simulated time (no hang on any byte stream).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "devices/joint_bus/bus_master.hpp"
#include "fuzz_link.hpp"
#include "portable/joint_bus_codes.hpp"

namespace {

using namespace armctl;
using namespace armctl::joint_bus;
using armctl::fuzz::FuzzJointBusLink;

void check(bool ok, const char* what) { FuzzJointBusLink::expect(ok, what); }

std::int16_t word_at(const std::vector<std::uint8_t>& b, std::size_t i) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(b[i] | (b[i + 1] << 8)));
}

// The STATUS a joint sends on success, straight from the spec.
std::int16_t spec_success(Dialect d, std::int16_t command) {
  return d == Dialect::legacy ? command : static_cast<std::int16_t>(100 + 10 * command);
}

// The last transaction was a successful one of `command` with `joint`; returns its
// RESPONSE (or nothing for commands without one).
std::optional<std::int16_t> successful_transaction(const FuzzJointBusLink& link, Dialect d,
                                                   int joint, std::int16_t command,
                                                   bool returns_value) {
  check(!link.transactions().empty(), "success without a transaction");
  const auto& b = link.transactions().back();
  check(b.size() == (returns_value ? 6u : 4u), "success read other than READY [RESPONSE] STATUS");
  check(word_at(b, 0) == joint, "success with a READY other than the joint's number");
  check(word_at(b, b.size() - 2) == spec_success(d, command), "success without the success STATUS");
  if (!returns_value) return std::nullopt;
  return word_at(b, 2);
}

enum Op : std::uint8_t {
  op_ping, op_get_position, op_get_target, op_get_joint_number, op_check_target_reached,
  op_home, op_set_pid_state, op_set_speed, op_set_zone, op_drive_dist, op_drive_dist_max,
  op_drive_to, op_transact, op_drive_all, op_count
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 5) return 0;
  const int joints = 1 + data[0] % 7;
  const std::uint32_t baud = data[1] % 2 ? 115200 : 9600;
  MasterOptions options;
  options.dialect = data[2] % 2 ? Dialect::legacy : Dialect::standard;
  options.retries = data[3] % 3;
  options.verify = data[4] % 2;
  options.verify_position_tolerance = data[4] / 2 % 4;
  FuzzJointBusLink link(joints, baud);
  BusMaster master(link, options);
  const Duration wt = options.timing.word_timeout(baud);
  const Dialect d = options.dialect;

  std::size_t p = 5;
  while (p + 6 <= size) {
    const auto op = static_cast<Op>(data[p] % op_count);
    const int joint = data[p + 1] % 9;  // 0 and 8 never exist
    const auto value = static_cast<std::int16_t>(static_cast<std::uint16_t>(data[p + 2] | (data[p + 3] << 8)));
    const std::size_t chunk = std::min<std::size_t>(data[p + 4] % 64, size - p - 6);
    const Duration delay = wt * (data[p + 5] % 8) / 2;
    const std::uint8_t extra = data[p + 5] / 8;  // transact: which command
    link.give(std::span<const std::uint8_t>(data + p + 6, chunk), delay);
    p += 6 + chunk;

    link.clear_transactions();
    const TimePoint start = link.clock().now();
    const bool exists = joint >= 1 && joint <= joints;
    auto must_refuse = [&](const armctl::Error& e) {
      const JointFailure* failure = armctl::joint_bus::joint_failure(e);
      check(failure != nullptr, "every master error carries a JointFailure");
      const JointFailure& f = *failure;
      if (!exists) {
        check(f.kind == FailureKind::invalid_argument && !f.command_sent, "a missing joint refused");
        check(link.transactions().empty(), "nothing on the bus for a missing joint");
      }
      check(!e.message.empty(), "failure message");
    };

    switch (op) {
      case op_ping: {
        auto r = master.ping(joint, value);
        if (r) {
          check(exists, "success with a missing joint");
          check(*r == value, "ping succeeded with a wrong echo");
          check(successful_transaction(link, d, joint, cmd_ping, true) == value, "ping value not from the bus");
        } else {
          must_refuse(r.error());
        }
        break;
      }
      case op_get_position:
      case op_get_target:
      case op_get_joint_number: {
        const std::int16_t cmd = op == op_get_position ? cmd_get_position
                                 : op == op_get_target ? cmd_get_target
                                                       : cmd_get_joint_number;
        auto r = op == op_get_position ? master.get_position(joint)
                 : op == op_get_target ? master.get_target(joint)
                                       : master.get_joint_number(joint);
        if (r) {
          check(exists, "success with a missing joint");
          check(successful_transaction(link, d, joint, cmd, true) == *r, "value not from the bus");
        } else {
          must_refuse(r.error());
        }
        break;
      }
      case op_check_target_reached: {
        auto r = master.check_target_reached(joint);
        if (r) {
          check(exists, "success with a missing joint");
          const auto v = successful_transaction(link, d, joint, cmd_check_target_reached, true);
          check(v == (*r ? 1 : 0), "reached flag not the 0/1 the joint sent");
        } else {
          must_refuse(r.error());
        }
        break;
      }
      case op_home:
      case op_set_pid_state:
      case op_set_speed:
      case op_set_zone: {
        const std::int16_t cmd = op == op_home ? cmd_home
                                 : op == op_set_pid_state ? cmd_set_pid_state
                                 : op == op_set_speed ? cmd_set_speed
                                                      : cmd_set_zone;
        auto r = op == op_home ? master.home(joint)
                 : op == op_set_pid_state ? master.set_pid_state(joint, value & 1)
                 : op == op_set_speed ? master.set_speed(joint, value)
                                      : master.set_zone(joint, value);
        if (r) {
          check(exists, "success with a missing joint");
          successful_transaction(link, d, joint, cmd, false);
        } else {
          must_refuse(r.error());
        }
        break;
      }
      case op_drive_dist:
      case op_drive_dist_max:
      case op_drive_to: {
        const Drive kind = op == op_drive_dist ? Drive::dist : op == op_drive_dist_max ? Drive::dist_max : Drive::to;
        auto r = master.drive(kind, joint, value);
        if (r) {
          check(exists, "success with a missing joint");
          if (!options.verify) {
            successful_transaction(link, d, joint, static_cast<std::int16_t>(kind), false);
          } else if (kind == Drive::to) {
            check(successful_transaction(link, d, joint, cmd_get_target, true) == value,
                  "verified drive_to with a target read back other than the value");
          } else if (kind == Drive::dist) {
            const auto after = successful_transaction(link, d, joint, cmd_get_target, true);
            bool before_seen = false;  // some earlier get_target answered after - value
            const auto& ts = link.transactions();
            for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
              if (ts[i].size() == 6 && word_at(ts[i], 0) == joint &&
                  word_at(ts[i], 4) == spec_success(d, cmd_get_target) &&
                  int(word_at(ts[i], 2)) + value == int(*after)) {
                before_seen = true;
              }
            }
            check(before_seen, "verified drive_dist without a matching target before");
          } else {
            successful_transaction(link, d, joint, cmd_get_position, true);
          }
        } else {
          must_refuse(r.error());
        }
        break;
      }
      case op_transact: {
        static const std::int16_t commands[] = {cmd_ping, cmd_home, cmd_get_position, cmd_drive_to,
                                                cmd_check_target_reached, 3, 99, -1};
        const std::int16_t cmd = commands[extra % 8];
        const CommandShape shape = command_shape(cmd);
        std::optional<std::int16_t> arg;
        if (value & 1) arg = value;
        auto r = master.transact(joint, cmd, arg);
        if (r) {
          check(exists, "success with a missing joint");
          check(!shape.known || shape.takes_data == arg.has_value(), "wrong data shape accepted");
          const auto v = successful_transaction(link, d, joint, cmd, shape.returns_value);
          check(*r == v, "response not from the bus");
          if (cmd == cmd_ping) check(*r == arg, "ping echo");
        } else {
          must_refuse(r.error());
        }
        break;
      }
      case op_drive_all: {
        std::vector<std::int16_t> values(static_cast<std::size_t>(joints), value);
        if (joint == 0) values.pop_back();  // a wrong count is refused for every joint
        const auto out = master.drive_all(Drive::to, values);
        check(out.size() == static_cast<std::size_t>(joints), "one result per joint");
        for (std::size_t i = 0; i < out.size(); ++i) {
          check(out[i].joint == int(i) + 1, "results in joint order");
          if (joint == 0) check(!out[i].result.ok(), "wrong value count refused");
        }
        break;
      }
      case op_count: break;
    }
    check(link.selected_count() == 0, "a select line left high after an operation");
    const int transactions_bound = 4 * (op == op_drive_all ? joints : 1) * (options.retries + 1);
    const Duration bound = delay + wire_time(chunk + 64, baud) + transactions_bound * (13 * wt);
    check(link.clock().now() - start <= bound, "operation took longer than its bounded time");
  }
  return 0;
}

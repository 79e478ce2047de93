// How one joint-bus transaction can fail. The master returns core's Result/Status like
// every library call; each Error it returns carries a JointFailure as its detail: the
// spec's code (910, 920, 930, 940, 990), the stage, the joint, the raw STATUS word when one
// arrived, and whether the COMMAND word went out on the wire (which decides whether a
// relative move may ever be retried). joint_failure(error) gets it back.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace armctl::joint_bus {

enum class FailureKind {
  wrong_joint,       // 910: READY was not the selected joint's number (master side)
  ping_bad_echo,     // 920: ping RESPONSE differs from its DATA (master side)
  unknown_command,   // 930: the joint does not know the command
  bad_data,          // 940: the joint refused the DATA (state unchanged)
  no_answer,         // 990: no READY / RESPONSE / STATUS before the timeout
  bad_status,        // STATUS is neither this command's success nor an error code
  verify_mismatch,   // verify-after-write read back a target other than the one given
  invalid_argument,  // the caller asked for something the master cannot send
  link,              // the link itself failed (the OS refused a read or write)
};

// The spec's code for a kind; 0 for kinds the spec has no code for.
int spec_code(FailureKind kind);
const char* to_string(FailureKind kind);

// Where in the transaction the failure happened (for messages and for retry decisions).
enum class Stage { before_command, ready, response, status, verify };
const char* to_string(Stage stage);

struct JointFailure {
  FailureKind kind;
  Stage stage;
  int joint;
  std::optional<std::int16_t> status_word;  // raw STATUS, if one was received
  bool command_sent;                        // the COMMAND word went out on the wire
  // FailureKind::link on a link that is lost and being reopened (its error carried a
  // ReconnectingLink's LinkLost): the device is gone for now, not this joint.
  bool link_lost = false;

  int code() const { return spec_code(kind); }
};

// timeout (990), device (930, 940, verify), invalid_argument, io (link: the master uses
// the link's own kind), else protocol.
ErrorKind error_kind(FailureKind kind);
// The Error for `failure`, with `message` (one line for people) and the failure as detail.
Error bus_error(const JointFailure& failure, std::string message);
// The JointFailure behind an error the master returned; nullptr for any other error.
inline const JointFailure* joint_failure(const Error& error) {
  return error.detail_as<JointFailure>();
}

}  // namespace armctl::joint_bus

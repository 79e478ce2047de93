#include "devices/joint_bus/bus_failure.hpp"

namespace armctl::joint_bus {

int spec_code(FailureKind kind) {
  switch (kind) {
    case FailureKind::wrong_joint: return 910;
    case FailureKind::ping_bad_echo: return 920;
    case FailureKind::unknown_command: return 930;
    case FailureKind::bad_data: return 940;
    case FailureKind::no_answer: return 990;
    case FailureKind::bad_status:
    case FailureKind::verify_mismatch:
    case FailureKind::invalid_argument:
    case FailureKind::link: return 0;
  }
  return 0;
}

const char* to_string(FailureKind kind) {
  switch (kind) {
    case FailureKind::wrong_joint: return "wrong joint";
    case FailureKind::ping_bad_echo: return "ping bad echo";
    case FailureKind::unknown_command: return "unknown command";
    case FailureKind::bad_data: return "bad data";
    case FailureKind::no_answer: return "no answer";
    case FailureKind::bad_status: return "bad status";
    case FailureKind::verify_mismatch: return "verify mismatch";
    case FailureKind::invalid_argument: return "invalid argument";
    case FailureKind::link: return "link failure";
  }
  return "failure";
}

const char* to_string(Stage stage) {
  switch (stage) {
    case Stage::before_command: return "before the command";
    case Stage::ready: return "waiting for READY";
    case Stage::response: return "waiting for RESPONSE";
    case Stage::status: return "waiting for STATUS";
    case Stage::verify: return "verifying";
  }
  return "?";
}

ErrorKind error_kind(FailureKind kind) {
  switch (kind) {
    case FailureKind::no_answer: return ErrorKind::timeout;
    case FailureKind::unknown_command:
    case FailureKind::bad_data:
    case FailureKind::verify_mismatch: return ErrorKind::device;
    case FailureKind::invalid_argument: return ErrorKind::invalid_argument;
    case FailureKind::link: return ErrorKind::io;
    case FailureKind::wrong_joint:
    case FailureKind::ping_bad_echo:
    case FailureKind::bad_status: return ErrorKind::protocol;
  }
  return ErrorKind::protocol;
}

Error bus_error(const JointFailure& failure, std::string message) {
  return Error{error_kind(failure.kind), std::move(message), failure};
}

}  // namespace armctl::joint_bus

// How one joint-bus transaction can fail, as a value: the spec's code (910, 920, 930, 940,
// 990), the raw STATUS word when one arrived, and whether the COMMAND word went out on the
// wire (which decides whether a relative move may ever be retried).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>

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
  std::string message;                      // one line for people

  int code() const { return spec_code(kind); }
  Error to_error() const;  // ErrorKind timeout/protocol/device/invalid_argument
};

// A value or a JointFailure (the joint bus analogue of core's Result).
template <typename T>
class BusResult {
 public:
  BusResult(T value) : v_(std::move(value)) {}              // NOLINT: implicit by design
  BusResult(JointFailure failure) : v_(std::move(failure)) {}  // NOLINT
  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  const T& value() const {
    if (!ok()) throw ArmctlError(failure().to_error());
    return std::get<0>(v_);
  }
  const T& operator*() const { return value(); }
  const JointFailure& failure() const { return std::get<1>(v_); }

 private:
  std::variant<T, JointFailure> v_;
};

struct Done {};  // the value of a command that returns nothing

}  // namespace armctl::joint_bus

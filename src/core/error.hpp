// The one error model of the host side (docs/architecture.md "Errors"): every library call
// that can fail returns Result<T> or Status, holding a value or an Error. An Error has a
// stable kind for programs, one line for people, and optionally a typed detail that a
// layer attaches for callers who need more than the kind (the joint bus attaches its
// JointFailure: spec code, stage, joint, raw STATUS, whether the command went out).
#pragma once

#include <any>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

namespace armctl {

enum class ErrorKind {
  invalid_argument,  // caller or user gave a value outside what is allowed
  invalid_config,    // a config or program file is malformed
  io,                // the operating system refused (open, read, write)
  timeout,           // a peer did not answer (or did not take our bytes) in time
  protocol,          // a peer answered with bytes the protocol does not allow
  device,            // a peer reported an error of its own, or refused a request
  unsupported,       // not available on this build or platform
};

const char* to_string(ErrorKind kind);

struct Error {
  ErrorKind kind;
  std::string message;
  // Empty, or one value of a type the producing layer documents (e.g. joint_bus::JointFailure).
  std::any detail{};

  // The detail if it is a D, else nullptr.
  template <typename D>
  const D* detail_as() const {
    return std::any_cast<D>(&detail);
  }
  // The same error with its message prefixed ("joint 3: " + message); kind and detail kept.
  Error prefixed(const std::string& prefix) const {
    return Error{kind, prefix + message, detail};
  }
};

// Thrown only where a call cannot return a Result: constructors, Result::value() on an
// error, and the byte-pipe interfaces under the library (see docs/architecture.md).
class ArmctlError : public std::runtime_error {
 public:
  explicit ArmctlError(Error e) : std::runtime_error(e.message), error_(std::move(e)) {}
  ArmctlError(ErrorKind kind, std::string message)
      : ArmctlError(Error{kind, std::move(message)}) {}
  const Error& error() const { return error_; }

 private:
  Error error_;
};

// A value or an error (std::expected is C++23; this is the small subset we need).
// [[nodiscard]]: a call that can fail is looked at; where ignoring the outcome is right, the
// caller says so with (void) and a comment why.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}  // NOLINT: implicit by design
  Result(Error error) : v_(std::move(error)) {}  // NOLINT
  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  const T& value() const& {
    if (!ok()) throw ArmctlError(error());
    return std::get<0>(v_);
  }
  T& value() & {
    if (!ok()) throw ArmctlError(error());
    return std::get<0>(v_);
  }
  T&& value() && {
    if (!ok()) throw ArmctlError(error());
    return std::get<0>(std::move(v_));
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }
  const Error& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

struct Ok {};
using Status = Result<Ok>;

// Runs `f` (which may throw ArmctlError, e.g. a constructor or a byte pipe) and returns
// its result, or the thrown error: where a throwing layer meets a Result-returning API.
template <typename F>
auto catch_error(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const ArmctlError& e) {
    return e.error();
  }
}

}  // namespace armctl

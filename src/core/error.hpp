// One error type for the host side: a stable code for programs, a message for people.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

namespace armctl {

enum class ErrorKind {
  invalid_argument,  // caller or user gave a value outside what is allowed
  invalid_config,    // a config or program file is malformed
  io,                // the operating system refused (open, read, write)
  timeout,           // a peer did not answer in time
  protocol,          // a peer answered with bytes the protocol does not allow
  device,            // a peer reported an error of its own
  unsupported,       // not available on this build or platform
};

const char* to_string(ErrorKind kind);

struct Error {
  ErrorKind kind;
  std::string message;
};

// Thrown at API boundaries where a call cannot return a Result (constructors, CLI parsing).
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
template <typename T>
class Result {
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
  const T* operator->() const { return &value(); }
  const Error& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

struct Ok {};
using Status = Result<Ok>;

}  // namespace armctl

// A refused API request: the HTTP status and one message for people that names what was
// wrong and what is allowed (docs/http-api.md "Errors"). Thrown by request parsing and the
// handlers, turned into {"error": message} with that status by the router; a refusal is
// thrown before anything is sent to the arm.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "devices/robot_commands/group_start.hpp"
#include "session/arm_worker.hpp"

namespace armctl::web {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
  // A refusal that is an armctl error: its message, and the error kept for its detail.
  ApiError(int status, Error error) : std::runtime_error(error.message), status_(status), error_(std::move(error)) {}
  int status() const { return status_; }
  // The armctl error behind it (with its typed detail), or nullptr.
  const Error* error() const { return error_ ? &*error_ : nullptr; }

 private:
  int status_;
  std::optional<Error> error_;
};

// The status of an armctl error, from its kind and typed detail (never its text): a bad
// value 400; an unsupported feature, the worker busy or a stop that dropped the job
// (session::JobRefused busy/dropped), a group the board did not start
// (robot_commands::GroupNotStarted) 409; anything else the device or the operating system
// said 500.
inline int status_of(const Error& e) {
  switch (e.kind) {
    case ErrorKind::invalid_argument:
    case ErrorKind::invalid_config: return 400;
    case ErrorKind::unsupported: return 409;
    default: break;
  }
  if (const auto* refused = session::job_refusal(e); refused && refused->reason != session::JobRefused::Reason::closing)
    return 409;
  if (robot_commands::group_not_started(e)) return 409;
  return 500;
}

[[noreturn]] inline void fail(const Error& e) { throw ApiError(status_of(e), e); }

// core/must.hpp's must for the HTTP API: the error thrown is the ApiError with its status,
// so that what the request helpers throw is one type, whoever calls them.
template <typename T>
T must(Result<T> r) {
  if (!r) fail(r.error());
  return std::move(r).value();
}


}  // namespace armctl::web

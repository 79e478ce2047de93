// A refused API request: the HTTP status and one message for people that names what was
// wrong and what is allowed (docs/http-api.md "Errors"). Thrown by request parsing and the
// handlers, turned into {"error": message} with that status by the router; a refusal is
// thrown before anything is sent to the arm.
#pragma once

#include <stdexcept>
#include <string>

#include "core/error.hpp"

namespace armctl::web {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

// The status of an armctl error: a bad value 400; the worker busy, an unsupported feature
// 409; anything the device or the operating system said 500.
inline int status_of(const Error& e) {
  switch (e.kind) {
    case ErrorKind::invalid_argument:
    case ErrorKind::invalid_config: return 400;
    case ErrorKind::unsupported: return 409;
    default:
      // The worker's refusals: a job runs ("busy: ..."), a stop dropped this one; the board's:
      // a group that did not start (empty or erased).
      return e.message.rfind("busy", 0) == 0 || e.message.find("stopped before it started") != std::string::npos ||
                     e.message.find("did not start") != std::string::npos
                 ? 409
                 : 500;
  }
}

[[noreturn]] inline void fail(const Error& e) { throw ApiError(status_of(e), e.message); }

template <typename T>
T must(Result<T> r) {
  if (!r) fail(r.error());
  return std::move(r).value();
}

}  // namespace armctl::web

// The value of a Result, or its error thrown as ArmctlError: where a Result meets code that
// reports errors by throwing (the CLI's commands; the HTTP API's handlers and the Python
// module, whose one catch of ArmctlError turns it into a status code or armctl.Error). The
// one such helper: before, each app had its own.
#pragma once

#include <utility>

#include "core/error.hpp"

namespace armctl {

template <typename T>
T must(Result<T> r) {
  return std::move(r).value();
}
inline void must(const Status& s) {
  if (!s) throw ArmctlError(s.error());
}

}  // namespace armctl

// The value of a Result, or its error thrown as ArmctlError: where a Result meets code that
// reports errors by throwing (the CLI's commands; the Python module, whose exception
// translator turns ArmctlError into armctl.Error). The one such helper: the CLI had three and
// the Python module its own. The HTTP API keeps web::must, which throws its ApiError.
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

// What every binding of the armctl Python module shares: armctl's errors raised as the one
// Python exception type armctl.Error (with .kind), and Ctrl-C seen while the GIL is released
// (docs/python.md "Errors", "Ctrl-C").
#pragma once

#include <optional>
#include <string>

#include <pybind11/pybind11.h>

#include "core/error.hpp"

namespace armctl::python {

namespace py = pybind11;

// Creates armctl.Error (a RuntimeError subclass) in `m` and registers the translation of
// ArmctlError into it.
void define_error(py::module_& m);

// Raises armctl.Error with `error`'s kind and message (throws py::error_already_set).
[[noreturn]] void raise(const Error& error);
[[noreturn]] void raise(ErrorKind kind, const std::string& message);

// The value, or armctl.Error.
template <typename T>
T must(Result<T> r) {
  if (!r) raise(r.error());
  return std::move(r.value());
}
inline void must(const Status& s) {
  if (!s) raise(s.error());
}

// Watches for a pending Python signal (SIGINT: KeyboardInterrupt) while the GIL is
// released: check() takes the GIL for a moment and runs Python's signal handlers; once one
// raised, check() stays true and rethrow() raises that exception (with the GIL held).
// Handlers run only on the main thread: elsewhere check() is always false.
class InterruptWatch {
 public:
  InterruptWatch() = default;
  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;
  ~InterruptWatch();

  bool check();  // call without the GIL
  bool tripped() const { return pending_ != nullptr; }
  [[noreturn]] void rethrow();  // call with the GIL, only when tripped()

 private:
  PyObject* type_ = nullptr;
  PyObject* pending_ = nullptr;
  PyObject* traceback_ = nullptr;
};

}  // namespace armctl::python

// What every binding of the armctl Python module shares: armctl's errors raised as the one
// Python exception type armctl.Error (with .kind), Ctrl-C seen while the GIL is released, and
// one device used from several Python threads (docs/python.md "Errors", "Ctrl-C", "Threads").
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include <pybind11/pybind11.h>

#include "core/error.hpp"
#include "core/must.hpp"

namespace armctl::python {

namespace py = pybind11;

// Creates armctl.Error (a RuntimeError subclass) in `m` and registers the translation of
// ArmctlError into it.
void define_error(py::module_& m);

// Raises armctl.Error with `error`'s kind and message (throws py::error_already_set).
[[noreturn]] void raise(const Error& error);
[[noreturn]] void raise(ErrorKind kind, const std::string& message);


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

// One device (an armctl.Arm, an armctl.RobotCommands connection) shared by Python threads.
// Nothing below it is thread-safe (arm::Arm, the Robot Commands client, a link carries one
// request and its reply at a time), so its calls take turns, in the order they came: each
// bound call holds a Turn from start to end. A turn is waited for with the GIL released,
// since the call that runs may need the GIL to finish (NumPy results, Ctrl-C checks).
// close() first marks the device closing, which running calls see at their next check (a
// wait ends, a streamed motion stops on its path), then waits for its own turn to end the
// device. stop() asks the same of the calls before it: a stop must not wait for a 10 s move.
class DeviceGate {
 public:
  // Held for one call; ends the turn when it goes.
  class Turn {
   public:
    Turn(Turn&& other) noexcept : gate_(std::exchange(other.gate_, nullptr)) {}
    Turn(const Turn&) = delete;
    Turn& operator=(const Turn&) = delete;
    Turn& operator=(Turn&&) = delete;
    ~Turn() {
      if (gate_) gate_->leave();
    }

   private:
    friend class DeviceGate;
    explicit Turn(DeviceGate* gate) : gate_(gate) {}
    DeviceGate* gate_;
  };

  // `what` names the device in errors: "Arm", "RobotCommands connection".
  explicit DeviceGate(const char* what) : what_(what) {}
  DeviceGate(const DeviceGate&) = delete;
  DeviceGate& operator=(const DeviceGate&) = delete;

  // This call's turn (call with the GIL); armctl.Error once close() has begun, or when the
  // thread that has the turn calls again (a signal handler or a callback run during a call):
  // waiting for itself would hang it.
  Turn enter();
  // Marks the device closing and waits for the running call to end (call with the GIL; it
  // is released while waiting). The closer ends the device while it holds the turn.
  Turn close();
  // A stop's turn: until it comes, the calls before it stop at their next check. From a
  // signal handler on the thread that has the turn: nullopt, that call alone is asked.
  std::optional<Turn> stop();
  // While a long session holds the turn across calls (a servo session), what it is: a call
  // from its own thread is refused naming it. nullptr when it ends.
  void set_session(const char* session) { session_ = session; }
  // True once close() has begun: a running call stops at its next check. Any thread.
  bool closing() const { return closing_.load(); }
  // True while a stop waits for its turn (or was asked during the running call).
  bool stop_asked() const { return stops_waiting_.load() > 0 || stop_here_.load(); }
  // armctl.Error (invalid_argument) for a call on a closed device; `during` says what ran
  // when close() ended it ("" for a call that came later).
  [[noreturn]] void raise_closed(const std::string& during = "") const;

 private:
  bool held_here() const { return owner_.load() == std::this_thread::get_id(); }
  void refuse_nesting() const;
  Turn wait_for_turn();
  void leave();

  std::mutex mutex_;  // guards the tickets; never held while a call runs
  std::condition_variable next_;
  std::uint64_t tickets_ = 0;  // handed out
  std::uint64_t serving_ = 0;  // the ticket whose call runs (or may run)
  std::atomic<std::thread::id> owner_{};  // the thread that has the turn, or none
  std::atomic<bool> closing_{false};
  std::atomic<int> stops_waiting_{0};
  std::atomic<bool> stop_here_{false};  // asked by a signal handler during the running call
  std::atomic<const char*> session_{nullptr};
  const char* what_;
};

}  // namespace armctl::python

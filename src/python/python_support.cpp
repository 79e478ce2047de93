#include "python_support.hpp"

#include <fmt/core.h>

#include "arm/motion_executor.hpp"
#include "arm/plan_moves.hpp"
#include "core/source_place.hpp"
#include "devices/joint_bus/reconnecting_link.hpp"
#include "motion/cartesian_path.hpp"

namespace armctl::python {

namespace {

PyObject* error_type = nullptr;  // armctl.Error, owned by the module

// The enumerator's name, as a program tests it (to_string gives words for people).
const char* kind_name(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::invalid_argument: return "invalid_argument";
    case ErrorKind::invalid_config: return "invalid_config";
    case ErrorKind::io: return "io";
    case ErrorKind::timeout: return "timeout";
    case ErrorKind::protocol: return "protocol";
    case ErrorKind::device: return "device";
    case ErrorKind::unsupported: return "unsupported";
  }
  return "device";
}

}  // namespace

void define_error(py::module_& m) {
  error_type = PyErr_NewExceptionWithDoc(
      "armctl.Error",
      "Every failure armctl reports: a refused value, a device that does not answer, a move that\n"
      "did not arrive. A subclass of RuntimeError; str(e) is the message, e.kind armctl's error\n"
      "kind: 'invalid_argument', 'invalid_config', 'io', 'timeout', 'protocol', 'device' or\n"
      "'unsupported', e.message the message. e.detail names what more it carries (None, or\n"
      "'following_error' with e.joint, e.measured, e.planned, e.limit; 'path_refusal' with\n"
      "e.segment, e.fraction, e.point, e.joint; 'collision' with e.bodies (the two that would touch),\n"
      "e.depth (m), e.fraction (of the motion), e.point (the tool point, m); 'source_place' with e.file,\n"
      "e.line, e.column;\n"
      "'device_lost').",
      PyExc_RuntimeError, nullptr);
  if (!error_type) throw py::error_already_set();
  m.add_object("Error", py::handle(error_type));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ArmctlError& e) {
      try {
        raise(e.error());
      } catch (py::error_already_set& set) {
        set.restore();
      }
    }
  });
}

namespace {

void set_place(py::object& e, const SourcePlace& at) {
  e.attr("file") = at.file;
  e.attr("line") = at.line;
  e.attr("column") = at.column;
}

// The error's typed detail as attributes (docs/python.md "Errors"): e.detail names which
// detail it carried (None: none), and its fields follow.
void set_detail(py::object& e, const Error& error) {
  e.attr("detail") = py::none();
  if (const auto* f = arm::following_error_of(error)) {
    e.attr("detail") = "following_error";
    e.attr("joint") = f->name;
    e.attr("measured") = f->measured;
    e.attr("planned") = f->planned;
    e.attr("limit") = f->limit;
  } else if (const auto* st = arm::stall_of(error)) {
    e.attr("detail") = "stall";
    e.attr("joint") = st->name;
    e.attr("position") = st->position;
    e.attr("driven_to") = st->driven_to;
    e.attr("seconds") = st->seconds;
  } else if (const auto* r = motion::path_refusal_of(error)) {
    e.attr("detail") = "path_refusal";
    e.attr("segment") = r->segment;
    e.attr("fraction") = r->fraction ? py::object(py::float_(*r->fraction)) : py::none();
    e.attr("point") = r->point ? py::object(py::make_tuple(r->point->x(), r->point->y(), r->point->z())) : py::none();
    e.attr("joint") = r->joint >= 0 ? py::object(py::str(r->joint_name)) : py::none();
  } else if (const auto* c = detail_or_cause<arm::CollisionDetail>(error)) {
    // A limit broken (the fence, a reduced joint range) is told apart from two bodies touching.
    e.attr("detail") = c->contact.limit == scene::Limit::none ? "collision" : "limit";
    e.attr("broken_limit") =
        c->contact.limit == scene::Limit::none ? py::object(py::none()) : py::object(py::str(scene::to_string(c->contact.limit)));
    e.attr("bodies") = py::make_tuple(c->contact.first, c->contact.second);
    e.attr("depth") = c->contact.depth;
    e.attr("fraction") = c->fraction;
    e.attr("point") = py::make_tuple(c->tool_point.x(), c->tool_point.y(), c->tool_point.z());
    // Found while moving (the scene changed under the motion): the arm stopped before it.
    e.attr("while_moving") = c->while_moving;
    // A program's line whose move it is: where, as a source_place detail says it.
    if (const auto* at = source_place(error)) set_place(e, *at);
  } else if (const auto* at = source_place(error)) {
    e.attr("detail") = "source_place";
    set_place(e, *at);
  } else if (joint_bus::device_lost(error)) {
    e.attr("detail") = "device_lost";
  }
}

}  // namespace

void raise(const Error& error) {
  py::object e = py::reinterpret_borrow<py::object>(error_type)(error.message);
  e.attr("kind") = kind_name(error.kind);
  e.attr("message") = error.message;
  set_detail(e, error);
  PyErr_SetObject(error_type, e.ptr());
  throw py::error_already_set();
}

void raise(ErrorKind kind, const std::string& message) { raise(Error{kind, message}); }

InterruptWatch::~InterruptWatch() {
  if (!pending_ && !type_ && !traceback_) return;
  py::gil_scoped_acquire gil;
  Py_XDECREF(type_);
  Py_XDECREF(pending_);
  Py_XDECREF(traceback_);
}

bool InterruptWatch::check() {
  if (pending_) return true;
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() == 0) return false;
  PyErr_Fetch(&type_, &pending_, &traceback_);
  PyErr_NormalizeException(&type_, &pending_, &traceback_);
  if (!pending_) {  // a handler that raised without a value: keep the type
    pending_ = type_;
    Py_XINCREF(pending_);
  }
  return true;
}

void InterruptWatch::rethrow() {
  PyErr_Restore(type_, pending_, traceback_);
  type_ = pending_ = traceback_ = nullptr;
  throw py::error_already_set();
}

void DeviceGate::refuse_nesting() const {
  if (const char* session = session_.load(); session && held_here())
    raise(ErrorKind::invalid_argument,
          fmt::format("this {} is in {} on this thread: its calls wait until the session ends (use the "
                      "session's status for where the arm is)",
                      what_, session));
  if (held_here())
    raise(ErrorKind::invalid_argument,
          fmt::format("this {} is already running a call on this thread (a signal handler or a callback called it "
                      "during another call): calls cannot nest",
                      what_));
}

DeviceGate::Turn DeviceGate::wait_for_turn() {
  refuse_nesting();
  std::unique_lock lock(mutex_);
  const std::uint64_t ticket = tickets_++;
  if (serving_ != ticket) {
    lock.unlock();  // not held while the GIL is taken back
    py::gil_scoped_release nogil;
    lock.lock();
    next_.wait(lock, [&] { return serving_ == ticket; });
    lock.unlock();
  }
  owner_ = std::this_thread::get_id();
  return Turn(this);
}

void DeviceGate::leave() {
  owner_ = std::thread::id{};
  stop_here_ = false;  // asked of the call that has ended
  {
    const std::lock_guard lock(mutex_);
    ++serving_;
  }
  next_.notify_all();
}

DeviceGate::Turn DeviceGate::enter() {
  if (closing()) raise_closed();
  Turn turn = wait_for_turn();
  if (closing()) raise_closed();  // closed while this call waited for its turn
  return turn;
}

DeviceGate::Turn DeviceGate::close() {
  refuse_nesting();
  closing_ = true;
  return wait_for_turn();
}

std::optional<DeviceGate::Turn> DeviceGate::stop() {
  if (held_here()) {
    stop_here_ = true;
    return std::nullopt;
  }
  ++stops_waiting_;
  struct Arrived {  // the calls after this stop run as usual, also when enter() raises
    std::atomic<int>& waiting;
    ~Arrived() { --waiting; }
  } arrived{stops_waiting_};
  return enter();
}

void DeviceGate::raise_closed(const std::string& during) const {
  raise(ErrorKind::invalid_argument, during.empty() ? fmt::format("this {} is closed", what_)
                                                    : fmt::format("this {} was closed during {}", what_, during));
}

}  // namespace armctl::python

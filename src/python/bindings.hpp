// The parts of the armctl Python module, each defined into the module by its own file.
#pragma once

#include <pybind11/pybind11.h>

#include "devices/robot_commands/client.hpp"

namespace armctl::python {

namespace py = pybind11;

void define_arm(py::module_& m);             // arm_bindings.cpp: Arm, Lin, Circ and their values
void define_robot_commands(py::module_& m);  // robot_commands_bindings.cpp: RobotCommands

// The action-group notifications `client` has queued, and those that arrive within
// `timeout` s, as dicts {kind, group, count}; the GIL is released while receiving.
py::list group_events(robot_commands::Client& client, double timeout);

// Runs `f` with the GIL released and returns what it returns.
template <typename F>
auto released(F&& f) -> decltype(f()) {
  py::gil_scoped_release nogil;
  return f();
}

}  // namespace armctl::python

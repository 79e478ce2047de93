// The parts of the armctl Python module, each defined into the module by its own file.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <pybind11/pybind11.h>

#include "arm/action_groups.hpp"
#include "arm/arm.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::python {

namespace py = pybind11;

void define_arm(py::module_& m);             // arm_bindings.cpp: Arm, Lin, Circ and their values
void define_robot_commands(py::module_& m);  // robot_commands_bindings.cpp: RobotCommands
void define_calibration(py::module_& m);     // calibration_bindings.cpp: Calibration

class DeviceGate;

// An armctl.Calibration over `arm` (Arm.calibration()); `board`: the Robot Commands board the
// xArm's servo IDs and offsets are reached through, or nullptr.
py::object make_calibration(arm::Arm& arm, DeviceGate& gate, robot_commands::Client* board, bool servo_offsets);

// The action-group notifications the client has queued, and those that arrive within
// `timeout` s, as dicts {kind, group, count}. Receives in short turns on `gate` (the GIL
// released meanwhile), so that other threads' calls (a run_group, a stop_group) go between
// them and a close() does not wait for the timeout; `client()` gives the client during a turn.
// One overload per source: a board's client (RobotCommands), an arm device's action groups (Arm).
py::list group_events(DeviceGate& gate, const std::function<robot_commands::Client&()>& client, double timeout);
py::list group_events(DeviceGate& gate, const std::function<arm::ActionGroups&()>& groups, double timeout);

// Runs `f` with the GIL released and returns what it returns.
template <typename F>
auto released(F&& f) -> decltype(f()) {
  py::gil_scoped_release nogil;
  return f();
}

}  // namespace armctl::python

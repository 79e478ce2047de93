// The armctl Python module's native part, armctl._armctl; the package (armctl/__init__.py)
// re-exports it with the pure-Python drop-in armctl.xarm. Docs: docs/python.md.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "python_support.hpp"

PYBIND11_MODULE(_armctl, m) {
  m.doc() =
      "armctl: drive, simulate and program the xArm and the SCARA arm (docs/python.md).\n\n"
      "armctl.Arm is the Arm API in SI units on any device URI (the embedded simulators by default);\n"
      "armctl.RobotCommands speaks to a Robot Commands board in device units; armctl.xarm is a drop-in\n"
      "for scripts written for the `xarm` package. Every failure raises armctl.Error (.kind, .message).";
  m.attr("__version__") = ARMCTL_VERSION;  // the project's version, as `armctl --version` says it
  armctl::python::define_error(m);
  armctl::python::define_calibration(m);
  armctl::python::define_arm(m);
  armctl::python::define_robot_commands(m);
}

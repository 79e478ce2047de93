# The Python module `armctl` (src/python, docs/python.md): pybind11 (Debian pybind11-dev)
# against Debian's Python 3 (python3-dev), pinned to /usr/bin/python3 so that a pyenv or
# virtualenv python first on PATH does not change what is built or where it is installed.
#   ARMCTL_PYTHON  ON: required (configuring fails, naming what is missing), OFF, or AUTO
#                  (default: built when pybind11 and the Python headers are found)
set(ARMCTL_PYTHON AUTO CACHE STRING "Build the Python module (pybind11): ON, OFF or AUTO")
set_property(CACHE ARMCTL_PYTHON PROPERTY STRINGS AUTO ON OFF)
set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python the module is built for")

if(ARMCTL_FUZZ)
  set(ARMCTL_PYTHON_ENABLED OFF)
  return()
endif()
string(TOUPPER "${ARMCTL_PYTHON}" _py)
if(_py MATCHES "^(OFF|NO|FALSE|N|0)$")
  set(ARMCTL_PYTHON_ENABLED OFF)
  return()
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module)
set(_py_found FALSE)
if(Python3_FOUND)
  # pybind11's own FindPython use follows ours.
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG QUIET)
  if(pybind11_FOUND)
    set(_py_found TRUE)
  endif()
endif()
armctl_resolve_part(ARMCTL_PYTHON ${_py_found}
                    "pybind11 or the Python 3 headers not found (Debian: pybind11-dev python3-dev)")
if(ARMCTL_PYTHON_ENABLED)
  # The static libraries go into a shared module.
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  # Where `make install` puts the package: Debian's python3 looks in
  # /usr/local/lib/python3.N/dist-packages (where pip installs too); lib/python3/dist-packages
  # is on its path only under /usr, the prefix of Debian's own packages.
  set(ARMCTL_PYTHON_INSTALL_DIR
      lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages CACHE STRING
      "Install folder of the armctl Python package, under the prefix")
endif()

# The parts that need more than a host compiler: the joint firmware (avr-g++, Debian gcc-avr
# avr-libc) and the HIL tests and firmware benchmark that run it on emulated chips (simavr,
# Debian simavr libsimavr-dev libelf-dev). The SDK and the CLI never need them.
#   ON    required: configuring fails, naming what is missing
#   OFF   not built
#   AUTO  (default) built when the tools are found, else skipped with a message saying so
# `make test` and `make bench` pass ON for both, so a missing tool fails them loudly.
set(ARMCTL_FIRMWARE AUTO CACHE STRING "Build the joint firmware with avr-g++: ON, OFF or AUTO")
set_property(CACHE ARMCTL_FIRMWARE PROPERTY STRINGS AUTO ON OFF)
set(ARMCTL_HIL AUTO CACHE STRING
    "Build the HIL tests and firmware benchmark (the firmware on simavr): ON, OFF or AUTO")
set_property(CACHE ARMCTL_HIL PROPERTY STRINGS AUTO ON OFF)

# armctl_resolve_part(NAME FOUND MISSING): sets NAME_ENABLED from NAME (ON/OFF/AUTO) and
# whether its tools were FOUND; MISSING says what is not there and how to get it.
function(armctl_resolve_part name found missing)
  set(value "${${name}}")
  string(TOUPPER "${value}" value)
  if(value STREQUAL "AUTO")
    if(found)
      set(enabled ON)
    else()
      set(enabled OFF)
      message(STATUS "${name}: off, ${missing} (-D${name}=ON to require it)")
    endif()
  elseif(value MATCHES "^(ON|YES|TRUE|Y|1)$")
    if(NOT found)
      message(FATAL_ERROR "${name}=ON, but ${missing} (or configure with -D${name}=OFF)")
    endif()
    set(enabled ON)
  elseif(value MATCHES "^(OFF|NO|FALSE|N|0)$")
    set(enabled OFF)
  else()
    message(FATAL_ERROR "${name}='${${name}}': allowed ON, OFF or AUTO")
  endif()
  set(${name}_ENABLED ${enabled} PARENT_SCOPE)
endfunction()

if(ARMCTL_FUZZ)
  # The fuzz build (clang) builds parsers only.
  set(ARMCTL_FIRMWARE_ENABLED OFF)
  set(ARMCTL_HIL_ENABLED OFF)
else()
  find_program(ARMCTL_AVR_GXX avr-g++)
  find_program(ARMCTL_AVR_OBJCOPY avr-objcopy)
  if(ARMCTL_AVR_GXX AND ARMCTL_AVR_OBJCOPY)
    set(_avr_found TRUE)
  else()
    set(_avr_found FALSE)
  endif()
  armctl_resolve_part(ARMCTL_FIRMWARE ${_avr_found}
                      "avr-g++/avr-objcopy not found (Debian: gcc-avr avr-libc binutils-avr)")

  pkg_check_modules(SIMAVR IMPORTED_TARGET simavr)
  pkg_check_modules(LIBELF IMPORTED_TARGET libelf)
  if(NOT ARMCTL_FIRMWARE_ENABLED)
    set(_hil_found FALSE)
    set(_hil_missing "it runs the firmware, and ARMCTL_FIRMWARE is off")
  elseif(NOT SIMAVR_FOUND OR NOT LIBELF_FOUND)
    set(_hil_found FALSE)
    set(_hil_missing "simavr/libelf not found (Debian: simavr libsimavr-dev libelf-dev)")
  else()
    set(_hil_found TRUE)
    set(_hil_missing "")
  endif()
  armctl_resolve_part(ARMCTL_HIL ${_hil_found} "${_hil_missing}")
endif()

# The ROS 1 node armctl_ros (src/ros, docs/ros.md): Debian's roscpp, actionlib, tf2_ros and
# message packages, and the message generators (genmsg, gencpp, actionlib_msgs' genaction)
# that make the FollowJointTrajectory action locally. ON/OFF/AUTO as above; `make test`
# passes ON.
set(ARMCTL_ROS AUTO CACHE STRING "Build the ROS 1 node armctl_ros: ON, OFF or AUTO")
set_property(CACHE ARMCTL_ROS PROPERTY STRINGS AUTO ON OFF)
if(ARMCTL_FUZZ)
  set(ARMCTL_ROS_ENABLED OFF)
else()
  pkg_check_modules(ROS IMPORTED_TARGET roscpp actionlib tf2_ros)
  find_path(ARMCTL_ROS_MSG_HEADERS NAMES sensor_msgs/JointState.h trajectory_msgs/JointTrajectory.h
            diagnostic_msgs/DiagnosticArray.h geometry_msgs/PoseStamped.h std_srvs/Trigger.h
            actionlib_msgs/GoalStatusArray.h)
  foreach(h sensor_msgs/BatteryState.h trajectory_msgs/JointTrajectory.h diagnostic_msgs/DiagnosticArray.h
            geometry_msgs/PoseStamped.h std_srvs/SetBool.h actionlib_msgs/GoalStatusArray.h)
    if(NOT ARMCTL_ROS_MSG_HEADERS OR NOT EXISTS ${ARMCTL_ROS_MSG_HEADERS}/${h})
      set(_ros_missing_header ${h})
    endif()
  endforeach()
  find_program(ARMCTL_GENACTION genaction.py PATHS /usr/lib/actionlib_msgs NO_DEFAULT_PATH)
  find_program(ARMCTL_GENCPP gen_cpp.py PATHS /usr/lib/gencpp NO_DEFAULT_PATH)
  find_file(ARMCTL_GENCPP_TEMPLATES msg.h.template PATHS /usr/share/gencpp NO_DEFAULT_PATH)
  find_program(ARMCTL_ROSMASTER rosmaster)
  find_program(ARMCTL_ROBOT_STATE_PUBLISHER robot_state_publisher PATHS /usr/lib/robot_state_publisher
               NO_DEFAULT_PATH)
  if(NOT ROS_FOUND)
    set(_ros_missing "roscpp/actionlib/tf2_ros not found (Debian: libroscpp-dev libactionlib-dev libtf2-ros-dev)")
  elseif(_ros_missing_header)
    set(_ros_missing "${_ros_missing_header} not found (Debian: lib<package>-dev, e.g. libsensor-msgs-dev)")
  elseif(NOT ARMCTL_GENACTION OR NOT ARMCTL_GENCPP OR NOT ARMCTL_GENCPP_TEMPLATES)
    set(_ros_missing "the message generators not found (Debian: libactionlib-msgs-dev python3-gencpp python3-genmsg)")
  elseif(NOT ARMCTL_ROSMASTER OR NOT ARMCTL_ROBOT_STATE_PUBLISHER)
    set(_ros_missing "rosmaster/robot_state_publisher not found (Debian: python3-rosmaster ros-robot-state-publisher)")
  else()
    set(_ros_missing "")
  endif()
  if(_ros_missing STREQUAL "")
    set(_ros_found TRUE)
  else()
    set(_ros_found FALSE)
  endif()
  armctl_resolve_part(ARMCTL_ROS ${_ros_found} "${_ros_missing}")
endif()

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

# cmake -P run_consumer.cmake: installs the build tree BUILD_DIR into a temporary prefix, checks
# the package points only into that prefix, builds tests/install/consumer out of tree against it
# with find_package(armctl), and runs it. Variables: BUILD_DIR SOURCE_DIR WORK_DIR GENERATOR
# CXX_COMPILER CXX_FLAGS (the sanitizer flags of a sanitizer build, else empty).
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "failed (${status}): ${command}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

foreach(f lib/cmake/armctl/armctl-config.cmake lib/cmake/armctl/armctl-config-version.cmake
          lib/cmake/armctl/armctl-targets.cmake lib/libarmctl_core.a lib/libarmctl_device_registry.a
          include/armctl/devices/joint_bus/bus_master.hpp include/armctl/core/error.hpp
          share/armctl/scara.arm.json bin/armctl)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
if(EXISTS ${prefix}/lib/libarmctl_joint_avr.a OR EXISTS ${prefix}/include/armctl/devices/joint_avr)
  message(FATAL_ERROR "the GPL test tool armctl_joint_avr was installed")
endif()
# A package that names the source or build tree works only on this machine, only until
# that tree moves.
file(GLOB package_files ${prefix}/lib/cmake/armctl/*.cmake)
foreach(f IN LISTS package_files)
  file(READ ${f} text)
  foreach(tree ${SOURCE_DIR} ${BUILD_DIR})
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${f} names ${tree}")
    endif()
  endforeach()
endforeach()

run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    -DCMAKE_PREFIX_PATH=${prefix})
string(FIND "${last_output}" "from ${prefix}/lib/cmake/armctl" at)
if(at EQUAL -1)
  message(FATAL_ERROR "find_package(armctl) did not use the package in ${prefix}:\n${last_output}")
endif()
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
# The installed configs, not the source tree's: ARMCTL_CONFIG_DIR comes first.
run(${CMAKE_COMMAND} -E env ARMCTL_CONFIG_DIR=${prefix}/share/armctl ARMCTL_STATE_DIR=${WORK_DIR}/state
    ${WORK_DIR}/build/consumer)
message(STATUS "${last_output}")
string(FIND "${last_output}" "consumer: joint 2 echoed 4321" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the consumer did not report its run:\n${last_output}")
endif()

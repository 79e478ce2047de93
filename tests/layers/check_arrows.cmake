# Configures tests/layers/arrows twice: the right arrows must configure, the wrong one must
# fail naming the library, its layer and the one it links. Run with -DROOT=<source> -DWORK=<dir>.
foreach(wrong OFF ON)
  file(REMOVE_RECURSE ${WORK}/${wrong})
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${ROOT}/tests/layers/arrows -B ${WORK}/${wrong}
                          -DARMCTL_ROOT=${ROOT} -DWRONG_ARROW=${wrong}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(wrong STREQUAL "OFF" AND NOT rc EQUAL 0)
    message(FATAL_ERROR "the right arrows did not configure:\n${out}${err}")
  endif()
  if(wrong STREQUAL "ON")
    if(rc EQUAL 0)
      message(FATAL_ERROR "a library linking a layer above its own configured:\n${out}${err}")
    endif()
    string(REGEX REPLACE "[ \t\r\n]+" " " flat "${err}")  # CMake wraps its messages
    string(FIND "${flat}" "armctl_low (layer low) links armctl_high (layer high), a layer above its own" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "the configure failed, but not with the layer check's message:\n${err}")
    endif()
  endif()
endforeach()

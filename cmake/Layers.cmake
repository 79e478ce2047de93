# armctl_library(name [NO_INSTALL] DEPS deps...): one static library per source folder, made of
# every .cpp in it, so adding a file needs no CMake edit. Header-only folders become INTERFACE.
# Unless NO_INSTALL, `cmake --install` puts the library in lib/, its headers in
# include/armctl/<folder under src/> (so `#include "devices/joint_bus/bus_master.hpp"` works
# as in this tree) and the target in the armctl package as armctl::<name without armctl_>
# (cmake/Install.cmake).
# Each library records its layer, the first folder of its path under src/ (src/devices/joint_bus:
# devices), for armctl_check_layers.
function(armctl_library name)
  cmake_parse_arguments(L "NO_INSTALL" "" "DEPS" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  set(includes $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/src> $<INSTALL_INTERFACE:include/armctl>)
  if(srcs)
    add_library(${name} STATIC ${srcs})
    target_include_directories(${name} PUBLIC ${includes})
    target_link_libraries(${name} PUBLIC ${L_DEPS})
    # The headers need C++20: a project that links the installed library gets it without
    # setting CMAKE_CXX_STANDARD. Only on the install interface: in this tree the standard is
    # set once (CMakeLists.txt), and the ROS node's own files must stay C++17.
    target_compile_features(${name} INTERFACE $<INSTALL_INTERFACE:cxx_std_20>)
    armctl_warnings(${name})
  else()
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${includes})
    target_link_libraries(${name} INTERFACE ${L_DEPS})
    target_compile_features(${name} INTERFACE $<INSTALL_INTERFACE:cxx_std_20>)
  endif()
  file(RELATIVE_PATH under_src ${CMAKE_SOURCE_DIR}/src ${CMAKE_CURRENT_SOURCE_DIR})
  string(REGEX REPLACE "/.*" "" layer "${under_src}")
  set_property(TARGET ${name} PROPERTY ARMCTL_LAYER ${layer})
  set_property(GLOBAL APPEND PROPERTY ARMCTL_LIBRARIES ${name})
  if(NOT L_NO_INSTALL)
    string(REGEX REPLACE "^armctl_" "" export_name ${name})
    set_target_properties(${name} PROPERTIES EXPORT_NAME ${export_name})
    add_library(armctl::${export_name} ALIAS ${name})
    install(TARGETS ${name} EXPORT armctl-targets ARCHIVE DESTINATION lib)
    file(RELATIVE_PATH folder ${CMAKE_SOURCE_DIR}/src ${CMAKE_CURRENT_SOURCE_DIR})
    file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.hpp)
    install(FILES ${headers} DESTINATION include/armctl/${folder})
  endif()
endfunction()

# armctl_bench(name SOURCES ... LIBS ...): a benchmark binary in <build>/bench/, run by make bench.
function(armctl_bench name)
  cmake_parse_arguments(B "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${B_SOURCES})
  target_link_libraries(${name} PRIVATE ${B_LIBS})
  # bench/bench_report.hpp: the CPU clock and the BENCH line every benchmark prints.
  target_include_directories(${name} PRIVATE ${CMAKE_SOURCE_DIR}/bench)
  target_compile_definitions(${name} PRIVATE ARMCTL_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    ARMCTL_BINARY_DIR="${CMAKE_BINARY_DIR}")
  armctl_warnings(${name})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
endfunction()

# armctl_fuzz(name SOURCES ... LIBS ...): a libFuzzer target in <build>/fuzz/ (clang only).
function(armctl_fuzz name)
  cmake_parse_arguments(F "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${F_SOURCES})
  target_link_libraries(${name} PRIVATE ${F_LIBS})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  add_dependencies(armctl_fuzz_all ${name})
endfunction()

# armctl_forbid_links(target FORBIDDEN libs...): fails the configure if `target` links any of
# `libs`, directly or through its dependencies. Holds the layering of docs/architecture.md
# (the host SDK links no simulator) where a wrong target_link_libraries would break it quietly.
# What `target` links itself (privately or in its interface), as written.
function(_armctl_direct_links target out)
  get_target_property(type ${target} TYPE)
  set(deps)
  if(NOT type STREQUAL "INTERFACE_LIBRARY")
    get_target_property(direct ${target} LINK_LIBRARIES)
    if(direct)
      list(APPEND deps ${direct})
    endif()
  endif()
  get_target_property(iface ${target} INTERFACE_LINK_LIBRARIES)
  if(iface)
    list(APPEND deps ${iface})
  endif()
  set(${out} ${deps} PARENT_SCOPE)
endfunction()

function(_armctl_collect_links target out)
  set(seen ${${out}})
  if(NOT TARGET ${target} OR ${target} IN_LIST seen)
    return()
  endif()
  list(APPEND seen ${target})
  _armctl_direct_links(${target} deps)
  foreach(dep IN LISTS deps)
    _armctl_collect_links(${dep} seen)
  endforeach()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

# WHY: what the message says after "it must not"; by default, the simulators' rule.
function(armctl_forbid_links target)
  cmake_parse_arguments(F "" "WHY" "FORBIDDEN" ${ARGN})
  if(NOT F_WHY)
    set(F_WHY "a simulator: simulators are opened through armctl_device_registry")
  endif()
  set(all)
  _armctl_collect_links(${target} all)
  foreach(lib IN LISTS F_FORBIDDEN)
    if(lib IN_LIST all)
      message(FATAL_ERROR "${target} links ${lib}: it must not (${F_WHY}; docs/architecture.md)")
    endif()
  endforeach()
endfunction()

# armctl_check_layers(layers...): fails the configure if any library made by armctl_library
# links (directly; what it links in turn is checked as its own library) a library of a layer
# later in `layers` than its own: each layer may link only itself and the layers before it.
# Every library's layer must be in the list. Run once, after every library is defined.
function(armctl_check_layers)
  set(layers ${ARGN})
  list(JOIN layers ", " order)
  get_property(libs GLOBAL PROPERTY ARMCTL_LIBRARIES)
  foreach(lib IN LISTS libs)
    get_target_property(layer ${lib} ARMCTL_LAYER)
    list(FIND layers "${layer}" rank)
    if(rank EQUAL -1)
      message(FATAL_ERROR "${lib} is in layer '${layer}', which the layer order (${order}) does not name: "
                          "add it where it belongs (src/CMakeLists.txt, docs/architecture.md)")
    endif()
    _armctl_direct_links(${lib} deps)
    foreach(dep IN LISTS deps)
      if(NOT TARGET ${dep})
        continue()
      endif()
      get_target_property(real ${dep} ALIASED_TARGET)
      if(real)
        set(dep ${real})
      endif()
      get_target_property(dep_layer ${dep} ARMCTL_LAYER)
      if(NOT dep_layer)
        continue()  # not one of ours (fmt, Eigen, ...)
      endif()
      list(FIND layers "${dep_layer}" dep_rank)
      if(dep_rank GREATER rank)
        message(FATAL_ERROR "${lib} (layer ${layer}) links ${dep} (layer ${dep_layer}), a layer above its own: "
                            "a layer may link only the layers before it (${order}; docs/architecture.md)")
      endif()
    endforeach()
  endforeach()
endfunction()

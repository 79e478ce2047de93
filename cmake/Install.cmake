# `cmake --install BUILD [--prefix DIR]` (make install: a Release build into /usr/local):
#   bin/armctl                              the CLI
#   lib/libarmctl_*.a                       the libraries (static)
#   include/armctl/<folder>/*.hpp           their headers, laid out as under src/
#   lib/cmake/armctl/                       the CMake package: find_package(armctl) gives
#                                           armctl::core, armctl::joint_bus,
#                                           armctl::robot_commands, armctl::device_registry, ...
#   share/armctl/                           the default configs (core/config_files.hpp)
# The udev rule goes to /etc (make install), outside any prefix.
if(ARMCTL_FUZZ)
  return()
endif()

include(CMakePackageConfigHelpers)

if(TARGET armctl)
  install(TARGETS armctl RUNTIME DESTINATION bin)
endif()
install(DIRECTORY ${CMAKE_SOURCE_DIR}/config/ DESTINATION share/armctl)

set(ARMCTL_PACKAGE_DIR lib/cmake/armctl)
install(EXPORT armctl-targets NAMESPACE armctl:: DESTINATION ${ARMCTL_PACKAGE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/armctl-config.cmake.in
  ${CMAKE_BINARY_DIR}/armctl-config.cmake INSTALL_DESTINATION ${ARMCTL_PACKAGE_DIR})
# 0.x: a new minor version may change the API.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/armctl-config-version.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/armctl-config.cmake ${CMAKE_BINARY_DIR}/armctl-config-version.cmake
  ${CMAKE_SOURCE_DIR}/cmake/ompl-target.cmake
  DESTINATION ${ARMCTL_PACKAGE_DIR})

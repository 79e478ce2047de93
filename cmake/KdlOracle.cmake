# KDL (Orocos) and its URDF parser: the independent oracle of the kinematics tests and the
# comparison of the kinematics benchmark. Never linked into armctl's libraries.
include_guard(GLOBAL)
pkg_check_modules(OROCOS_KDL REQUIRED IMPORTED_TARGET orocos-kdl)
# kdl_parser's pkg-config file requires ROS packages Debian does not ship as .pc files;
# the library itself needs only urdfdom and KDL.
find_library(KDL_PARSER_LIBRARY kdl_parser REQUIRED)
add_library(armctl_kdl_oracle INTERFACE)
target_link_libraries(armctl_kdl_oracle INTERFACE ${KDL_PARSER_LIBRARY} PkgConfig::OROCOS_KDL PkgConfig::URDFDOM)
target_include_directories(armctl_kdl_oracle INTERFACE ${CMAKE_SOURCE_DIR}/tests/motion)

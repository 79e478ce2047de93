# OMPL 1.5's package config (find_package(ompl)) gives variables, not a target: wrap them as
# ompl::ompl so that armctl_arm links it like its other dependencies, in this tree and in the
# installed package (armctl-config.cmake includes this file). The include directory is an
# imported target's, so OMPL's headers compile as system headers under the project's
# warnings-as-errors. Only OMPL's own directory: OMPL_INCLUDE_DIRS also names /usr/include,
# which as a system directory would break libstdc++'s #include_next.
if(NOT TARGET ompl::ompl)
  add_library(ompl::ompl INTERFACE IMPORTED)
  set_target_properties(ompl::ompl PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${OMPL_LIBRARIES}")
endif()

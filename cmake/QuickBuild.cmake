# ARMCTL_QUICK_BUILD (make demo passes ON): the first build of the armctl CLI on a small
# machine in less time. The dashboard server (armctl_web) compiles as a unity build, its
# files a few at a time in one compiler run: each of them parses cpp-httplib, nlohmann/json
# and fmt, and together they took 94 s of CPU of the CLI's 437 s; as a unity build, 23 s
# (the Release armctl from nothing on 2 cores: 3 min 43 s before, 3 min 6 s after; README.md
# "Quick start"). Measured and left out:
#  - a unity build of the other libraries and the CLI's own files: it fails (file-local
#    helpers of the same name, refuse(), usage(), kPi, ...), and where it compiled the
#    libraries gained little;
#  - a precompiled header of CLI11, nlohmann/json, fmt and Eigen for the CLI's files: they took
#    as long with it (147 s of CPU) as without (146 s): their time is code generation.
# Off by default: a unity build hides a missing #include in one file behind another, so the
# everyday builds keep one file, one compiler run.
option(ARMCTL_QUICK_BUILD "Unity build of the dashboard server armctl_web (make demo)" OFF)
if(ARMCTL_QUICK_BUILD AND TARGET armctl_web)
  set_target_properties(armctl_web PROPERTIES UNITY_BUILD ON)
  # The embedded dashboard files: its OBJECT_DEPENDS (a changed file is embedded again) would
  # be lost inside a unity source.
  set_source_files_properties(${CMAKE_BINARY_DIR}/src/web/web_assets_table.cpp DIRECTORY ${CMAKE_SOURCE_DIR}/src/web
                              PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
endif()

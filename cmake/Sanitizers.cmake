# The test build (make test) runs everything under ASan and UBSan; any report fails the test.
if(ARMCTL_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
  # Line tables only: every report still names file and line, and the build compiles and
  # links faster with binaries a fraction of the size (this build has some sixty).
  add_compile_options(-g1)
endif()
if(ARMCTL_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer)
  # Line tables only, as the test build: a finding's stack still names file and line.
  add_compile_options(-gline-tables-only)
  add_link_options(-fsanitize=address,undefined)
endif()

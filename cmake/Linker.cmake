# lld links the test build's large debug executables several times faster than the default
# GNU ld (measured: build/armctl 15.6 s with ld.bfd, 3.6 s with ld.lld), and this build
# links some sixty of them. Debian's lld package; without it, the default linker.
include(CheckLinkerFlag)
check_linker_flag(CXX "-fuse-ld=lld" ARMCTL_HAVE_LLD)
if(ARMCTL_HAVE_LLD)
  add_link_options(-fuse-ld=lld)
endif()

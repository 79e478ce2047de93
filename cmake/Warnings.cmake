# Project code compiles warning-free with -Wall -Wextra; warnings are errors in our targets.
function(armctl_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Werror)
endfunction()

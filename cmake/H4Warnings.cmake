# Warnings as errors for the project's own code only: h4_target_warnings(target).
# Third-party headers come in as SYSTEM includes so their warnings stay theirs.
function(h4_target_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion-null
    -Wimplicit-fallthrough)
  # Not in sanitizer builds: GCC 12's flow warnings (-Wmaybe-uninitialized in <regex>) give
  # false positives under -fsanitize at -O2; those builds are for run-time findings.
  if(NOT H4_SANITIZE)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

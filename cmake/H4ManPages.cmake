# Man pages of the programs, generated from their own --help by Debian's help2man, so they
# never disagree with the program: h4_add_man_page(TARGET SUMMARY COMPONENT...) runs, after TARGET
# is built, `TARGET --help`, `TARGET --version` and `TARGET SUBCOMMAND --help` for every
# subcommand (cmake/H4ManPageGenerate.cmake) and installs TARGET.1 in share/man/man1 for
# each COMPONENT. Not in a cross build (the program cannot run at build time) nor in a
# sanitizer build (never installed); without help2man the pages are left out with a
# warning (scripts/setup installs it).
find_program(H4_HELP2MAN help2man)
set(H4_MAN_PAGES OFF)
if(H4_HELP2MAN AND NOT CMAKE_CROSSCOMPILING AND NOT H4_SANITIZE)
  set(H4_MAN_PAGES ON)
elseif(NOT H4_HELP2MAN AND NOT CMAKE_CROSSCOMPILING)
  message(WARNING "help2man not found: no man pages (Debian: apt-get install help2man)")
endif()

function(h4_add_man_page target summary)
  if(NOT H4_MAN_PAGES OR NOT TARGET ${target})
    return()
  endif()
  set(page ${PROJECT_BINARY_DIR}/man/${target}.1)
  # EXIT STATUS, FILES and EXAMPLES, which --help does not carry: cmake/man/TARGET.h2m.
  set(sections ${PROJECT_SOURCE_DIR}/cmake/man/${target}.h2m)
  add_custom_command(
    OUTPUT ${page}
    COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:${target}> -DNAME=${target} "-DSUMMARY=${summary}"
            -DHELP2MAN=${H4_HELP2MAN} -DOUTPUT=${page} -DSECTIONS=${sections}
            -P ${PROJECT_SOURCE_DIR}/cmake/H4ManPageGenerate.cmake
    DEPENDS ${target} ${PROJECT_SOURCE_DIR}/cmake/H4ManPageGenerate.cmake ${sections}
    COMMENT "help2man: ${target}.1"
    VERBATIM)
  add_custom_target(${target}_man_page ALL DEPENDS ${page})
  foreach(component IN LISTS ARGN)
    install(FILES ${page} DESTINATION share/man/man1 COMPONENT ${component})
  endforeach()
endfunction()

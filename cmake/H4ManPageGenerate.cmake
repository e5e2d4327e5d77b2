# Build-time half of cmake/H4ManPages.cmake: the man page of one program from its --help.
#   cmake -DPROGRAM=path -DNAME=h4cal -DSUMMARY="what it is" -DHELP2MAN=path -DOUTPUT=h4cal.1
#         -DSECTIONS=cmake/man/h4cal.h2m -P H4ManPageGenerate.cmake
# help2man reads the program's --help and --version; the subcommands' --help (listed under
# "Subcommands:" in the program's --help) go into a SUBCOMMANDS section through
# help2man's --include file, so the page documents every option of every command; SECTIONS
# (help2man's include format) adds what --help does not say: EXIT STATUS, FILES, EXAMPLES.
foreach(variable PROGRAM NAME SUMMARY HELP2MAN OUTPUT SECTIONS)
  if(NOT ${variable})
    message(FATAL_ERROR "H4ManPageGenerate: -D${variable}=... is required")
  endif()
endforeach()

execute_process(COMMAND ${PROGRAM} --help OUTPUT_VARIABLE help RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "H4ManPageGenerate: '${PROGRAM} --help' exited ${status}")
endif()
# CLI11 2.3 heads the listing "Subcommands:" (other versions "SUBCOMMANDS:"); it ends at
# the first blank line.
set(subcommands)
set(in_listing OFF)
string(REPLACE "\n" ";" lines "${help}")
foreach(line IN LISTS lines)
  if(line MATCHES "^(Subcommands|SUBCOMMANDS):")
    set(in_listing ON)
  elseif(in_listing AND line MATCHES "^  ([a-z][a-z0-9-]*)( |$)")
    list(APPEND subcommands ${CMAKE_MATCH_1})
  elseif(in_listing AND line STREQUAL "")
    break()
  endif()
endforeach()
if(NOT subcommands)
  message(FATAL_ERROR "H4ManPageGenerate: '${PROGRAM} --help' lists no subcommand")
endif()

set(include_text "[SUBCOMMANDS]\n")
foreach(subcommand IN LISTS subcommands)
  execute_process(COMMAND ${PROGRAM} ${subcommand} --help OUTPUT_VARIABLE sub_help
                  RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "H4ManPageGenerate: '${PROGRAM} ${subcommand} --help' exited ${status}")
  endif()
  # CLI11's usage line names the program as it was run (the build path): name it as installed.
  string(REPLACE "${PROGRAM}" "${NAME}" sub_help "${sub_help}")
  # roff: a leading dot or quote would start a request; backslashes are escapes.
  string(REPLACE "\\" "\\e" sub_help "${sub_help}")
  string(REGEX REPLACE "\n([.'])" "\n\\\\&\\1" sub_help "${sub_help}")
  string(APPEND include_text ".SS \"${NAME} ${subcommand}\"\n.nf\n${sub_help}\n.fi\n")
endforeach()
file(READ ${SECTIONS} sections_text)
string(APPEND include_text "\n${sections_text}")
get_filename_component(directory ${OUTPUT} DIRECTORY)
file(MAKE_DIRECTORY ${directory})
file(WRITE ${OUTPUT}.include "${include_text}")

execute_process(
  COMMAND ${HELP2MAN} --no-info --no-discard-stderr --section=1
          --name=${SUMMARY} --include=${OUTPUT}.include --output=${OUTPUT} ${PROGRAM}
  RESULT_VARIABLE status ERROR_VARIABLE error)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "H4ManPageGenerate: help2man ${PROGRAM} failed: ${error}")
endif()

# h4_lcm_generate(TARGET name PACKAGE pkg FILES a.lcm b.lcm ...)
# Runs lcm-gen --cpp at build time (Debian's LCM 1.3.1 ships no CMake helpers) and
# makes an INTERFACE target whose include directory holds <pkg>/<type>.hpp.
find_program(LCM_GEN_EXECUTABLE lcm-gen REQUIRED)

function(h4_lcm_generate)
  cmake_parse_arguments(ARG "" "TARGET;PACKAGE" "FILES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/lcmtypes)
  set(headers)
  foreach(lcm_file ${ARG_FILES})
    get_filename_component(abs ${lcm_file} ABSOLUTE)
    # One type per file: <type>.lcm declares struct <type> in package <pkg>.
    get_filename_component(type ${lcm_file} NAME_WE)
    set(header ${out_dir}/${ARG_PACKAGE}/${type}.hpp)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${LCM_GEN_EXECUTABLE} --cpp --cpp-hpath ${out_dir} ${abs}
      DEPENDS ${abs}
      COMMENT "lcm-gen ${type}.lcm"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  add_custom_target(${ARG_TARGET}_gen DEPENDS ${headers})
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_gen)
  target_include_directories(${ARG_TARGET} SYSTEM INTERFACE ${out_dir})
  target_link_libraries(${ARG_TARGET} INTERFACE PkgConfig::LCM)
endfunction()

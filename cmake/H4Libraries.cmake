# One static library per source folder, named after what it does, with the folders and
# packages it uses listed: the build enforces the layering
# (docs/architecture.md#libraries-and-their-dependencies), and a user of one part links only what
# that part needs (h4::kinematics brings no LCM, NLopt or OpenCV).
#
#   h4_add_folder_library(<name> <folder> [PUBLIC deps...] [PRIVATE deps...])
#
# compiles <folder>/*.cpp into h4_<name> (alias h4::<name>); every library sees the
# repository root as its include root and links h4::common. A folder that only has headers
# gets an INTERFACE library.
function(h4_add_folder_library name folder)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${folder}/*.cpp)
  set(target h4_${name})
  if(sources)
    add_library(${target} STATIC ${sources})
    target_link_libraries(${target} PUBLIC h4::common ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
    h4_target_warnings(${target})
  else()
    add_library(${target} INTERFACE)
    target_link_libraries(${target} INTERFACE h4::common ${ARG_PUBLIC})
  endif()
  add_library(h4::${name} ALIAS ${target})
  set_property(GLOBAL APPEND PROPERTY H4_FOLDER_LIBRARIES ${target})
endfunction()

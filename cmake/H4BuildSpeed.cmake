# Build time of a full build (CI builds everything twice, scripts/test): -DH4_UNITY_BUILD=ON
# compiles each library's and test program's sources in batches (CMake unity build), so
# that the heavy headers (CLI11, spdlog/fmt, Eigen, OpenCV, nlohmann/json) are parsed and
# their templates instantiated once per batch instead of once per file. Off by default: an incremental
# build of one edited file stays one file. Included at the end of the top-level
# CMakeLists.txt, once every target exists.
#
# What a full build costs, measured: docs/development.md#ci-and-timings. Single files:
# four host/cli/*_command.cpp compiled one by one under -fsanitize took 97 s, as one unity
# file 27 s. Precompiled headers were tried and are not used: with GCC 12 a 220 MB
# precompiled header (-g) made files slower to compile (host/identification/
# identification.cpp 8.8 s -> 18.7 s, fk_command.cpp unchanged).
#
# Files in one batch share their anonymous namespaces: two files defining the same name
# there (e.g. the parameter indices kQ0... of model12.cpp and model31.cpp) must not be in
# one batch, hence the exclusions below (such a file is compiled on its own). A new clash
# shows as "redefinition of ... {anonymous}::name" in the unity build only.
option(H4_UNITY_BUILD "Compile libraries and test programs in unity batches (full builds, CI)" OFF)

function(h4_unity_exclude dir)
  foreach(file ${ARGN})
    if(EXISTS ${PROJECT_SOURCE_DIR}/${dir}/${file})
      set_source_files_properties(${PROJECT_SOURCE_DIR}/${dir}/${file}
                                  DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}
                                  PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
    endif()
  endforeach()
endfunction()

if(H4_UNITY_BUILD)
  get_property(folder_libraries GLOBAL PROPERTY H4_FOLDER_LIBRARIES)
  get_property(test_programs GLOBAL PROPERTY H4_TEST_PROGRAMS)  # tests/CMakeLists.txt
  foreach(target h4_common ${folder_libraries} ${test_programs})
    if(TARGET ${target})
      get_target_property(type ${target} TYPE)
      if(NOT type STREQUAL "INTERFACE_LIBRARY")
        set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
      endif()
    endif()
  endforeach()
  # model31.cpp: the same anonymous-namespace names as model12.cpp, other meanings. (Builds
  # without the host, such as the fuzz build, have no host directory to mark.)
  if(TARGET h4_kinematics)
    h4_unity_exclude(host kinematics/model31.cpp)
  endif()
endif()

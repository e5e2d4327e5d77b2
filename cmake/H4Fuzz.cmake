# The fuzz build (-DH4_FUZZ=ON, clang only; scripts/fuzz configures build-fuzz/): every
# object of ours gets libFuzzer's coverage instrumentation with AddressSanitizer and
# UndefinedBehaviorSanitizer, and tests/fuzz adds one libFuzzer program per file reader.
# Kept apart from the test builds: their objects must not carry fuzzer instrumentation.
option(H4_FUZZ "Build the libFuzzer targets of tests/fuzz (clang)" OFF)
if(H4_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "H4_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined -O1 -g)
  add_link_options(-fsanitize=address,undefined)
endif()

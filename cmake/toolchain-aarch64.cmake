# Cross-compiling h4cam for a 64-bit ARM camera module running Debian bookworm arm64.
# Compiler: Debian's g++-aarch64-linux-gnu. Libraries and headers: an arm64 root file
# system (the sysroot) that scripts/cross-build prepares; nothing arm64 is installed on the
# host itself, so the host's own -dev packages stay untouched.
#
#   cmake -S . -B build-aarch64 -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake \
#         -DH4_SYSROOT=/var/cache/h4cal/sysroot-bookworm-arm64 -DH4_BUILD_HOST=OFF
#
# Programs (lcm-gen, pkg-config) are the host's; libraries, headers and CMake package files
# come only from the sysroot. Test programs run under qemu-aarch64 with the sysroot's own
# loader and libraries (CMAKE_CROSSCOMPILING_EMULATOR, which gtest_discover_tests uses too).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

# The toolchain file is read again for every try_compile, where cache entries are not
# visible: the environment variable and CMAKE_TRY_COMPILE_PLATFORM_VARIABLES carry it there.
if(NOT H4_SYSROOT)
  if(DEFINED ENV{H4_SYSROOT})
    set(H4_SYSROOT "$ENV{H4_SYSROOT}")
  else()
    set(H4_SYSROOT "/var/cache/h4cal/sysroot-bookworm-arm64")
  endif()
endif()
set(H4_SYSROOT "${H4_SYSROOT}" CACHE PATH "arm64 root file system (scripts/cross-build makes it)")
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES H4_SYSROOT)
set(ENV{H4_SYSROOT} "${H4_SYSROOT}")
if(NOT EXISTS "${H4_SYSROOT}/usr/include/aarch64-linux-gnu")
  message(FATAL_ERROR "toolchain-aarch64: no arm64 sysroot at H4_SYSROOT='${H4_SYSROOT}' "
                      "(expected ${H4_SYSROOT}/usr/include/aarch64-linux-gnu); "
                      "run scripts/cross-build, which prepares it")
endif()

set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_SYSROOT "${H4_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH "${H4_SYSROOT}")

# NEVER for programs: find_program(lcm-gen) in H4Lcm.cmake must find the host's binary,
# which runs at build time; the sysroot's (if any) is an arm64 file.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The host's pkg-config reads only the sysroot's .pc files and prefixes their paths with
# the sysroot. pkg-config runs at configure time only, where this environment is in force.
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${H4_SYSROOT}")
set(ENV{PKG_CONFIG_LIBDIR}
    "${H4_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${H4_SYSROOT}/usr/lib/pkgconfig:${H4_SYSROOT}/usr/share/pkgconfig")
unset(ENV{PKG_CONFIG_PATH})

# Running aarch64 programs here: qemu user emulation with -L <sysroot>, so the program's
# interpreter (/lib/ld-linux-aarch64.so.1) and every library come from the sysroot.
# (-L /usr/aarch64-linux-gnu, the cross toolchain's partial libc, hangs threaded programs
# when libc6:arm64 is also installed; the sysroot is a complete, consistent bookworm libc.)
find_program(H4_QEMU_AARCH64 NAMES qemu-aarch64 qemu-aarch64-static)
if(H4_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${H4_QEMU_AARCH64};-L;${H4_SYSROOT}")
endif()

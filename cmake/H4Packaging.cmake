# The h4cam Debian package (CPack, DEB generator): /usr/bin/h4cam, the systemd unit
# h4cam.service, the default configuration /etc/h4cam/h4cam.yaml (a conffile), the board
# files and the maintainer scripts (firmware/packaging/). Built for the architecture being
# compiled: amd64 natively, arm64 with cmake/toolchain-aarch64.cmake.
#   cpack -G DEB        (in the build directory)  ->  h4cam_<version>_<arch>.deb
# Only the install() rules of component "h4cam" (firmware/CMakeLists.txt) are packaged.
#
# Depends: natively dpkg-shlibdeps computes them from the host's dpkg database. A cross
# build has no dpkg database for its arm64 libraries, so this file is included a second
# time by cpack (CPACK_PROJECT_CONFIG_FILE, H4_DEB_CPACK_TIME set): it reads h4cam's
# DT_NEEDED entries and maps each soname through the shlibs files of the sysroot's packages
# (recorded by scripts/cross-build in <sysroot>/.h4-shlibs), as dpkg-shlibdeps would.

# Shared libraries come from h4cam's DT_NEEDED entries either way, so libcrypto.so.3 (the
# HMAC of authenticated bus messages, messages/bus) brings libssl3 into Depends without a
# line here.
# Packages every h4cam needs beyond its shared libraries: adduser for the postinst, and
# libcamera-ipa: the image processing modules (Raspberry Pi, rkisp1, ...) that Debian's
# libcamera only suggests, without which its pipeline handlers find no usable camera.
set(H4_DEB_BASE_DEPENDS "adduser, libcamera-ipa")

if(H4_DEB_CPACK_TIME)
  # --- cpack time (cross builds): Depends from the binary and the sysroot's shlibs ---
  if(NOT EXISTS "${H4_DEB_BINARY}")
    message(FATAL_ERROR "H4Packaging: ${H4_DEB_BINARY} does not exist: build h4cam first")
  endif()
  if(NOT EXISTS "${H4_DEB_SHLIBS}")
    message(FATAL_ERROR "H4Packaging: no shlibs table ${H4_DEB_SHLIBS}: "
                        "the sysroot was not made by scripts/cross-build (run it again)")
  endif()
  execute_process(COMMAND "${H4_DEB_READELF}" -d "${H4_DEB_BINARY}"
                  OUTPUT_VARIABLE dynamic RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "H4Packaging: '${H4_DEB_READELF} -d ${H4_DEB_BINARY}' failed")
  endif()
  string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*\\[[^]\n]+\\]" needed_lines "${dynamic}")
  file(STRINGS "${H4_DEB_SHLIBS}" shlibs_lines)
  set(depends ${H4_DEB_BASE_DEPENDS})
  foreach(line IN LISTS needed_lines)
    string(REGEX REPLACE ".*\\[([^]]+)\\]" "\\1" soname "${line}")
    # deb-shlibs(5): libfoo.so.3 is "libfoo 3"; libfoo-1.2.so is "libfoo-1.2" with no version
    # ... written "libfoo 1.2" by some packages, so both keys are tried.
    set(keys)
    if(soname MATCHES "^(.+)\\.so\\.(.+)$")
      list(APPEND keys "${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ")
    elseif(soname MATCHES "^(.+)-([0-9.]+)\\.so$")
      list(APPEND keys "${CMAKE_MATCH_1}-${CMAKE_MATCH_2} " "${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ")
    endif()
    set(dependency)
    foreach(shlibs_line IN LISTS shlibs_lines)
      foreach(key IN LISTS keys)
        string(FIND "${shlibs_line}" "${key}" position)
        if(position EQUAL 0)
          string(LENGTH "${key}" key_length)
          string(SUBSTRING "${shlibs_line}" ${key_length} -1 dependency)
          string(STRIP "${dependency}" dependency)
          break()
        endif()
      endforeach()
      if(dependency)
        break()
      endif()
    endforeach()
    if(NOT dependency)
      message(FATAL_ERROR "H4Packaging: h4cam needs ${soname}, which no package of the "
                          "sysroot declares in its shlibs (${H4_DEB_SHLIBS})")
    endif()
    list(APPEND depends "${dependency}")
  endforeach()
  list(REMOVE_DUPLICATES depends)
  list(JOIN depends ", " CPACK_DEBIAN_PACKAGE_DEPENDS)
  message(STATUS "H4Packaging: Depends: ${CPACK_DEBIAN_PACKAGE_DEPENDS}")
  return()
endif()

# --- configure time ---
if(NOT H4_BUILD_FIRMWARE)
  return()
endif()

include(H4DebianArchitecture)
h4_debian_architecture(h4_deb_arch)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME h4cam)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR h4cal)
set(CPACK_PACKAGE_CONTACT "h4cal maintainers <maintainers@h4cal.invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "camera firmware of h4cal, vision-based calibration of H4 parallel robots")
# The extended description (CPack puts the summary above it and indents each line).
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "h4cam runs on the camera module fixed to the robot's base: it captures and averages
frames, detects the calibration board, estimates its pose with a covariance and
publishes it over LCM to the workstation program h4cal. It runs as the systemd
service h4cam.service under the dedicated user h4cam.")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE ${h4_deb_arch})
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # h4cam_<version>_<arch>.deb
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
# Poses are paired with joint readings by utime: the camera's clock must follow the host's.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "chrony | time-daemon")
set(CPACK_INSTALL_CMAKE_PROJECTS "${PROJECT_BINARY_DIR};${PROJECT_NAME};h4cam;/")

# conffiles: dpkg keeps local edits of the configuration across upgrades.
file(WRITE ${PROJECT_BINARY_DIR}/packaging/conffiles "/etc/h4cam/h4cam.yaml\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${PROJECT_SOURCE_DIR}/firmware/packaging/postinst
    ${PROJECT_SOURCE_DIR}/firmware/packaging/prerm
    ${PROJECT_SOURCE_DIR}/firmware/packaging/postrm
    ${PROJECT_BINARY_DIR}/packaging/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)

if(CMAKE_CROSSCOMPILING)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS OFF)
  if(TARGET h4cam)
    find_program(H4_READELF NAMES aarch64-linux-gnu-readelf readelf REQUIRED)
    file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/packaging/h4cam-cpack-config.cmake CONTENT
"# Generated by cmake/H4Packaging.cmake: Depends of the cross-built package at cpack time.
set(H4_DEB_CPACK_TIME ON)
set(H4_DEB_BINARY \"$<TARGET_FILE:h4cam>\")
set(H4_DEB_READELF \"${H4_READELF}\")
set(H4_DEB_SHLIBS \"${CMAKE_SYSROOT}/.h4-shlibs\")
include(\"${CMAKE_CURRENT_LIST_FILE}\")
")
    set(CPACK_PROJECT_CONFIG_FILE ${PROJECT_BINARY_DIR}/packaging/h4cam-cpack-config.cmake)
  endif()
else()
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "${H4_DEB_BASE_DEPENDS}")
endif()

include(CPack)

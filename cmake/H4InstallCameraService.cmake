# Run by `cmake --install` (install(SCRIPT), component h4cam; firmware/CMakeLists.txt): the
# camera service's systemd unit and default configuration.
# The package installs with prefix /usr, and these two mean something only where systemd and
# dpkg look: /lib/systemd/system/h4cam.service and /etc/h4cam/h4cam.yaml (a conffile).
# Any other prefix P keeps them inside it (P/lib/systemd/system, P/etc/h4cam), with the
# unit's paths rewritten to P's program and configuration, so that
# `cmake --install build --prefix P` writes nothing outside P.
# file(INSTALL) adds $DESTDIR itself, as the generated install rules do.
# Set by the install(CODE) before it: H4_CAMERA_PACKAGING_DIR (the sources) and
# H4_CAMERA_STAGING_DIR (a folder of the build tree for the rewritten unit).
if(NOT DEFINED H4_CAMERA_PACKAGING_DIR OR NOT DEFINED H4_CAMERA_STAGING_DIR)
  message(FATAL_ERROR "H4InstallCameraService: H4_CAMERA_PACKAGING_DIR or "
                      "H4_CAMERA_STAGING_DIR is not set")
endif()
if(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  set(h4_root "")
else()
  set(h4_root "${CMAKE_INSTALL_PREFIX}")
endif()
set(h4_unit_dir "${h4_root}/lib/systemd/system")
set(h4_config_dir "${h4_root}/etc/h4cam")

set(h4_mode FILE_PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
file(INSTALL "${H4_CAMERA_PACKAGING_DIR}/h4cam.yaml" DESTINATION "${h4_config_dir}" ${h4_mode})
if(h4_root STREQUAL "")
  file(INSTALL "${H4_CAMERA_PACKAGING_DIR}/h4cam.service" DESTINATION "${h4_unit_dir}" ${h4_mode})
else()
  # The unit names /usr/bin/h4cam, /etc/h4cam/h4cam.yaml and /usr/share/doc/h4cam: P's own.
  file(READ "${H4_CAMERA_PACKAGING_DIR}/h4cam.service" h4_unit)
  string(REPLACE "/usr/bin/h4cam" "${CMAKE_INSTALL_PREFIX}/bin/h4cam" h4_unit "${h4_unit}")
  string(REPLACE "/etc/h4cam/" "${h4_config_dir}/" h4_unit "${h4_unit}")
  string(REPLACE "/usr/share/doc/h4cam/" "${CMAKE_INSTALL_PREFIX}/share/doc/h4cam/" h4_unit
                 "${h4_unit}")
  set(h4_staged "${H4_CAMERA_STAGING_DIR}/h4cam.service")
  file(WRITE "${h4_staged}" "${h4_unit}")
  file(INSTALL "${h4_staged}" DESTINATION "${h4_unit_dir}" ${h4_mode})
endif()

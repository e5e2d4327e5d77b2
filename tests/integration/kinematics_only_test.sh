#!/usr/bin/env bash
# A kinematics-only user links no LCM, NLopt, OpenCV, AprilTag, libcamera or OpenSSL: the
# per-folder libraries (cmake/H4Libraries.cmake) keep them out. Checks the program's direct
# shared-library needs (readelf: works for a cross-built program too) and that it runs.
# Usage: kinematics_only_test.sh PROGRAM ROBOT_YAML
set -uo pipefail
program=$1 robot=$2
needed=$(readelf -d "$program" | grep NEEDED) || { echo "FAIL: readelf on $program"; exit 1; }
forbidden=$(echo "$needed" | grep -E 'liblcm|libnlopt|libopencv|libapriltag|libcamera|libcrypto|libssl|libspdlog' || true)
if [ -n "$forbidden" ]; then
  echo "FAIL: a kinematics-only program needs:"; echo "$forbidden"; exit 1
fi
out=$(${H4_TEST_EMULATOR:-} "$program" "$robot") || { echo "FAIL: $program exited $?"; exit 1; }
echo "$out"
echo "$out" | grep -qE 'round trip error [0-9.e-]+ m' || { echo "FAIL: unexpected output"; exit 1; }
echo "PASS: h4::kinematics alone; shared libraries:"; echo "$needed"

#!/usr/bin/env bash
# The dependency rule of the layout (docs/architecture.md#libraries-and-their-dependencies): common
# includes neither firmware, host nor messages; firmware never includes host; host never includes
# firmware; examples/ (the workstation side of the bus) never includes firmware; the host's
# libraries include only what they use.
set -uo pipefail
src=$1
status=0
check() {  # folder, forbidden include prefix regex
  local hits
  hits=$(grep -rnE "#include [\"<]($2)" "$src/$1" --include='*.h' --include='*.cpp' || true)
  if [ -n "$hits" ]; then
    echo "FAIL: $1/ must not include $2:"; echo "$hits"; status=1
  fi
}
check common 'firmware/|host/|messages/|h4msgs/|lcm/|opencv2/|apriltag|libcamera/|nlopt'
check firmware 'host/'
check host 'firmware/|opencv2/|apriltag|libcamera/'
# Inside the host, each library (and its test folder, whose program links that library alone)
# includes only the host libraries it uses: host/CMakeLists.txt, bottom up.
declare -A host_uses=(
  [kinematics]='kinematics'
  [formats]='kinematics|formats'
  [simulation]='kinematics|formats|simulation'
  [identification]='kinematics|formats|identification'
  [validation]='kinematics|formats|identification|simulation|validation'
  [report]='kinematics|formats|identification|simulation|validation|report'
  [planning]='kinematics|formats|identification|simulation|planning'
  [campaign]='kinematics|formats|simulation|campaign'
)
declare -A test_folder_of=([formats]=host_formats)
# The same on the camera side: firmware/CMakeLists.txt, bottom up. firmware/bench holds the
# benchmarks' scene helpers, which the tests of rendered scenes share.
declare -A firmware_uses=(
  [frames]='frames'
  [detection]='detection'
  [render]='detection|render|bench'
  [sources]='frames|detection|render|sources'
  [averaging]='frames|averaging'
  [pose]='frames|averaging|detection|pose'
  [calibration]='detection|calibration'
  [board_print]='detection|board_print'
  [service]='frames|averaging|detection|render|sources|pose|service|bench'
)
test_folder_of+=([sources]=frame_sources [service]=camera_service)
check_uses() {  # side (host or firmware), library, its folders' allowed includes
  local folder hits
  for folder in "$1/$2" "tests/${test_folder_of[$2]:-$2}"; do
    [ -d "$src/$folder" ] || continue
    hits=$(grep -rnE "#include \"$1/[a-z_]+/" "$src/$folder" --include='*.h' --include='*.cpp' |
           grep -vE "#include \"$1/($3)/" || true)
    if [ -n "$hits" ]; then
      echo "FAIL: $folder/ may include only $1/{$3}:"; echo "$hits"; status=1
    fi
  done
}
for library in "${!host_uses[@]}"; do check_uses host "$library" "${host_uses[$library]}"; done
for library in "${!firmware_uses[@]}"; do
  check_uses firmware "$library" "${firmware_uses[$library]}"
done
# The robot bridge example is the workstation's side of the bus: never the camera's code.
[ -d "$src/examples" ] && check examples 'firmware/|opencv2/|apriltag|libcamera/'
[ $status -eq 0 ] && echo "PASS: common pure; firmware and host independent; their libraries one-way"
exit $status

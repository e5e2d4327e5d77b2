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
# Inside each side, a library (and its test folder, whose program links that library alone)
# includes only the libraries it uses, bottom up as host/CMakeLists.txt and
# firmware/CMakeLists.txt list them. firmware/bench holds the benchmarks' scene helpers,
# which the tests of rendered scenes share.
declare -A uses=(
  [host/kinematics]='kinematics'
  [host/formats]='kinematics|formats'
  [host/simulation]='kinematics|formats|simulation'
  [host/identification]='kinematics|formats|identification'
  [host/validation]='kinematics|formats|identification|simulation|validation'
  [host/report]='kinematics|formats|identification|simulation|validation|report'
  [host/planning]='kinematics|formats|identification|simulation|planning'
  [host/campaign]='kinematics|formats|simulation|campaign'
  [firmware/frames]='frames'
  [firmware/detection]='detection'
  [firmware/render]='detection|render|bench'
  [firmware/sources]='frames|detection|render|sources'
  [firmware/averaging]='frames|averaging'
  [firmware/pose]='frames|averaging|detection|pose'
  [firmware/calibration]='detection|calibration'
  [firmware/board_print]='detection|board_print'
  [firmware/service]='frames|averaging|detection|render|sources|pose|service|bench'
)
declare -A test_folder_of=([host/formats]=host_formats [firmware/sources]=frame_sources
                           [firmware/service]=camera_service)
for library in "${!uses[@]}"; do
  side=${library%%/*}
  test_folder=tests/${test_folder_of[$library]:-${library#*/}}
  for folder in "$library" "$test_folder"; do
    [ -d "$src/$folder" ] || continue
    hits=$(grep -rnE "#include \"$side/[a-z_]+/" "$src/$folder" --include='*.h' --include='*.cpp' |
           grep -vE "#include \"$side/(${uses[$library]})/" || true)
    if [ -n "$hits" ]; then
      echo "FAIL: $folder/ may include only $side/{${uses[$library]}}:"; echo "$hits"; status=1
    fi
  done
done
# The robot bridge example is the workstation's side of the bus: never the camera's code.
[ -d "$src/examples" ] && check examples 'firmware/|opencv2/|apriltag|libcamera/'
[ $status -eq 0 ] && echo "PASS: common pure; firmware and host independent; their libraries one-way"
exit $status

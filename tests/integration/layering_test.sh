#!/usr/bin/env bash
# The dependency rule of the layout (docs/architecture.md#libraries-and-their-dependencies): common
# includes neither firmware, host nor messages; firmware never includes host; host never includes
# firmware; examples/ (the workstation side of the bus) never includes firmware.
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
# The robot bridge example is the workstation's side of the bus: never the camera's code.
[ -d "$src/examples" ] && check examples 'firmware/|opencv2/|apriltag|libcamera/'
[ $status -eq 0 ] && echo "PASS: common pure; firmware and host independent"
exit $status

#!/usr/bin/env bash
# The robot-bridge example (examples/robot_bridge, docs/robot-bridge.md) in place of
# `h4cal sim-robot`: the bridge with its simulated controller, the camera service on
# rendered frames and `h4cal collect` run as separate processes over UDP multicast in a
# private network namespace, and the campaign completes through the bridge: every planned
# pose recorded once, paired with joint readings the bridge published for that pose.
#   robot_bridge_test.sh H4CAL H4CAM BRIDGE SOURCE_DIR WORK_DIR
# Time limits scale with $H4_TEST_TIME_SCALE (the sanitizer build sets it).
set -euo pipefail
h4cal=$(realpath "$1") h4cam=$(realpath "$2") bridge=$(realpath "$3") src=$(realpath "$4")
dir=$(realpath -m "$5")
source "$src/tests/integration/live_test_lib.sh"
enter_private_netns "$0" "$@"

fail() { echo "FAIL: $*" >&2; for f in "$dir"/*.log; do echo "--- $f"; tail -n 5 "$f"; done >&2; exit 1; }

"$h4cal" simulate --truth 12 --seed 3 --robot-seed 3 --out-dir sim 2> simulate.log
cat > plan.csv <<'PLAN'
pose_id,X,Y,Z,theta
1,-0.05,-0.05,-0.45,0
2,0.05,-0.05,-0.45,0.2
3,0.05,0.05,-0.5,-0.2
4,-0.05,0.05,-0.4,0
PLAN

"$bridge" --truth sim/truth.yaml --joint-speed 2 --settle-time 0.1 > bridge.log 2>&1 &
pids+=($!)
"$h4cam" run --source sim --sim-preset clean --frames 3 \
  --board "$src/boards/aprilgrid_6x6_30mm.yaml" --camera "$src/boards/sim_camera_1024x768.yaml" \
  > camera.log 2>&1 &
pids+=($!)
"$h4cal" collect --plan plan.csv --out dataset.csv --settle-timeout $((20 * scale)) \
  --capture-timeout $((10 * scale)) > collect.log 2>&1 || fail "collect exited $?"
rows=$(( $(wc -l < dataset.csv) - 1 ))
[ "$rows" -eq 4 ] || fail "dataset.csv has $rows rows, expected 4"
[ "$(cut -d, -f1 dataset.csv | tail -n +2 | sort -n | tr '\n' ' ')" = "1 2 3 4 " ] \
  || fail "dataset.csv does not hold poses 1-4 once each"
grep -q "4 of 4 planned poses" collect.log || fail "collect did not record the 4 poses"
echo "PASS: a 4-pose campaign completed through the robot bridge example"

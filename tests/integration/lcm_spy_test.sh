#!/usr/bin/env bash
# scripts/lcm-spy, the shipped way to watch the traffic: (1) the Java types it builds decode
# every message of a real campaign log the way lcm-spy looks them up, on all eight H4_
# channels; (2) the spy GUI itself starts under OpenJDK 17 (on a virtual display) and is
# still running after a few seconds, with the eight types found.
#   lcm_spy_test.sh SOURCE_DIR LOGFILE
set -uo pipefail
src=$1 log=$2
for tool in java javac xvfb-run; do
  command -v $tool > /dev/null || { echo "SKIP: $tool missing (scripts/setup --spy)"; exit 77; }
done
if [ ! -f "$log" ]; then
  skipped=$(dirname "$log")/SKIPPED
  [ -f "$skipped" ] && { echo "SKIP: live_campaign skipped: $(cat "$skipped")"; exit 77; }
  echo "FAIL: no campaign log $log (the live_campaign test writes it)"; exit 1
fi

out=$("$src/scripts/lcm-spy" --check "$log" 2>&1) || { echo "$out"; echo "FAIL: --check"; exit 1; }
echo "$out"
for channel in H4_BOARD_POSE H4_BOARD_CORNERS H4_CAMERA_STATUS H4_CAPTURE_REQUEST H4_JOINT_STATE \
               H4_ROBOT_TARGET H4_SIM_BOARD_TRUTH H4_TARGET_STATUS; do
  echo "$out" | grep -qE "^$channel +h4msgs\.[a-z_]+ +decoded +[1-9][0-9]* +failed 0 " \
    || { echo "FAIL: $channel not decoded"; exit 1; }
done

gui=$(timeout 8 xvfb-run -a "$src/scripts/lcm-spy" --lcm-url 'memq://' 2>&1)
code=$?
echo "$gui"
[ $code -eq 124 ] || { echo "FAIL: lcm-spy exited $code instead of running"; exit 1; }
echo "$gui" | grep -q "Found 8 LCM types" || { echo "FAIL: spy did not find the 8 types"; exit 1; }
echo "PASS: eight channels decoded; lcm-spy runs"

#!/usr/bin/env bash
# A live campaign under a junk flood (tests/fuzz/README.md#the-campaign-under-a-flood):
# the simulated robot (h4cal sim-robot), the camera service on rendered frames (h4cam run
# --source sim) and `h4cal collect` over POSES poses of the paper's grid, while
# tests/fuzz/bus_flood.py sends RATE junk messages/s for SECONDS on every H4 channel.
# With --auth-key, the camera and the campaign share a fresh key. Passes when every pose is
# recorded. Run inside a private network namespace:
#   scripts/in-private-netns tests/fuzz/flood_campaign.sh H4CAL H4CAM OUT_DIR \
#       [--auth-key] [--poses 24] [--seconds 30] [--rate 2000]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
[ $# -ge 3 ] || { sed -n '2,9p' "$0" >&2; exit 2; }
h4cal=$(realpath "$1") h4cam=$(realpath "$2") out=$3
shift 3
auth=0 poses=24 seconds=30 rate=2000
while [ $# -gt 0 ]; do
  case "$1" in
    --auth-key) auth=1 ;;
    --poses) poses=$2; shift ;;
    --seconds) seconds=$2; shift ;;
    --rate) rate=$2; shift ;;
    *) echo "flood_campaign: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done
export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
mkdir -p "$out"
rm -f "$out/dataset.csv" "$out/dataset.corners.csv" "$out/warmup_dataset.csv" \
  "$out/warmup_dataset.corners.csv"

# The plan: the first POSES poses of the grid, as the a priori robot reaches them.
"$h4cal" simulate --paper --out-dir "$out/sim" > /dev/null 2>&1
cut -d, -f1,3-6 "$out/sim/dataset.csv" | head -n $((poses + 1)) > "$out/joints.csv"
"$h4cal" fk --robot "$out/sim/robot.yaml" --joints "$out/joints.csv" --out "$out/fk.csv" 2> /dev/null
cut -d, -f1-5 "$out/fk.csv" > "$out/plan.csv"
key=()
if [ $auth -eq 1 ]; then
  head -c 48 /dev/urandom > "$out/key" && chmod 600 "$out/key"
  key=(--auth-key "$out/key")
fi

pids=()
stop_all() { for p in "${pids[@]}"; do kill -TERM "$p" 2> /dev/null || true; done; wait 2> /dev/null || true; }
trap stop_all EXIT
"$h4cal" sim-robot --truth "$out/sim/truth.yaml" --robot "$out/sim/robot.yaml" \
  --joint-speed 1.0 > "$out/sim_robot.log" 2>&1 &
pids+=($!)
"$h4cam" run --source sim --board "$root/boards/aprilgrid_6x6_30mm.yaml" \
  --camera "$root/boards/sim_camera_1024x768.yaml" --camera-id sim-camera "${key[@]}" \
  > "$out/h4cam.log" 2>&1 &
pids+=($!)
# Recorded traffic the flood makes foreign: a short clean campaign of 3 poses.
rm -f "$out/traffic.lcmlog"
lcm-logger --quiet -f "$out/traffic.lcmlog" > /dev/null 2>&1 &
logger=$!
head -n 4 "$out/plan.csv" > "$out/warmup.csv"
"$h4cal" collect --plan "$out/warmup.csv" --out "$out/warmup_dataset.csv" "${key[@]}" \
  > "$out/warmup.log" 2>&1
kill -INT $logger; wait $logger || true  # the whole log on disk before the flood reads it

# The flood starts with the campaign and lasts SECONDS.
python3 "$root/tests/fuzz/bus_flood.py" "$out/traffic.lcmlog" --rate "$rate" \
  --seconds "$seconds" > "$out/flood.log" 2>&1 &
flood=$!
status=0
timecmd=()
[ -x /usr/bin/time ] && timecmd=(/usr/bin/time -v)
"${timecmd[@]}" "$h4cal" collect --plan "$out/plan.csv" --out "$out/dataset.csv" "${key[@]}" \
  > "$out/collect.log" 2>&1 || status=$?
wait $flood || true
recorded=$(($(wc -l < "$out/dataset.csv") - 1))
echo "flood_campaign: $recorded of $poses poses recorded (collect exit $status, key: $auth)"
cat "$out/flood.log"
grep -E "messages:|skipped|Maximum resident|Elapsed" "$out/collect.log" || true
[ "$recorded" -eq "$poses" ] && [ $status -eq 0 ]

#!/usr/bin/env bash
# The live system (issue "Live system", done-when): the simulated robot (h4cal sim-robot),
# the camera service on rendered frames (h4cam run --source sim) and the campaign
# (h4cal collect) run as separate processes over UDP multicast inside a private network
# namespace (loopback only), while the real lcm-logger records the traffic. Then:
#   - the 12-pose dataset identifies the true robot within the "Host solver" accuracy
#     (held-out board poses <= 0.10 mm / 0.02 deg RMS, Model 12);
#   - the log, read through LCM's file:// provider (collect --from-log) and replayed live by
#     the real lcm-logplayer into collect --passive, rebuilds the same rows byte for byte;
#   - a campaign interrupted (SIGINT, Ctrl-C) in the middle exits 130 with its rows flushed
#     and resumes; killed (SIGKILL) further on and started again, it ends with every pose
#     exactly once;
#   - all of it with authenticated messages (h4cam run --auth-key, collect --auth-key, one
#     pre-shared key): the signed log rebuilds the same rows through --from-log with the key
#     and lcm-logplayer into a listener without it, while a listener holding another key
#     records nothing and counts what it dropped.
#   live_campaign_test.sh H4CAL H4CAM SOURCE_DIR WORK_DIR
# Time limits (capture and settle timeouts, waits) are multiplied by $H4_TEST_TIME_SCALE
# (default 1; the sanitizer build sets it, cmake/H4Sanitizers.cmake: its renderer is ~7x
# slower, so a 10-frame capture takes longer than the plain build's 10 s capture timeout).
set -euo pipefail
h4cal=$(realpath "$1") h4cam=$(realpath "$2") src=$(realpath "$3") dir=$(realpath -m "$4")
source "$src/tests/integration/live_test_lib.sh"
enter_private_netns "$0" "$@"
for tool in lcm-logger lcm-logplayer; do
  command -v $tool > /dev/null || { echo "FAIL: $tool not installed"; exit 1; }
done

fail() { echo "FAIL: $*" >&2; for f in "$dir"/*.log; do echo "--- $f"; tail -n 5 "$f"; done >&2; exit 1; }
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'; }
rows() { [ -f "$1" ] && echo $(( $(wc -l < "$1") - 1 )) || echo 0; }
corner_poses() { tail -n +2 "$1" | cut -d, -f1 | sort -n | uniq | wc -l; }

# The pre-shared key, made as messages/README.md says.
(umask 077; head -c 32 /dev/urandom > h4.key)
(umask 077; head -c 32 /dev/urandom > other.key)

"$h4cal" simulate --truth 12 --seed 3 --robot-seed 3 --out-dir sim 2> simulate.log
cat > plan.csv <<'PLAN'
pose_id,X,Y,Z,theta
1,-0.1,-0.1,-0.525,-0.3490658503988659
2,0.1,-0.1,-0.525,0.3490658503988659
3,-0.1,0.1,-0.525,0.3490658503988659
4,0.1,0.1,-0.525,-0.3490658503988659
5,-0.1,-0.1,-0.375,0.3490658503988659
6,0.1,-0.1,-0.375,-0.3490658503988659
7,-0.1,0.1,-0.375,-0.3490658503988659
8,0.1,0.1,-0.375,0.3490658503988659
9,0,0,-0.45,-0.3490658503988659
10,0,0,-0.45,0
11,0,0,-0.45,0.3490658503988659
12,0,0.1,-0.45,0
PLAN

"$h4cal" sim-robot --truth sim/truth.yaml --joint-speed 2 --settle-time 0.1 > sim_robot.log 2>&1 &
robot=$!; pids+=($robot)
# The processed preset (the default): frames as a camera module's ISP delivers them
# (sRGB-like response, defocus, illumination gradient, shot noise).
"$h4cam" run --source sim --sim-preset processed --board "$src/boards/aprilgrid_6x6_30mm.yaml" \
  --camera "$src/boards/sim_camera_1024x768.yaml" --camera-id sim --auth-key h4.key \
  > camera.log 2>&1 &
camera=$!; pids+=($camera)
lcm-logger --quiet -f campaign.lcmlog > logger.log 2>&1 &
logger=$!; pids+=($logger)

# Frames averaged per measurement: the camera's 10, or 2 in the sanitizer pass ($scale > 1),
# whose renderer is ~7x slower: 10 frames there made this test take 890 s of a CI run whose
# sanitizer pass it ended (2 frames still hold the held-out accuracy checked below).
frames=$([ "$scale" -gt 1 ] && echo 2 || echo 10)
collect=("$h4cal" collect --plan plan.csv --frames $frames --settle-timeout $((20 * scale))
         --capture-timeout $((10 * scale)) --auth-key h4.key)
"${collect[@]}" --out dataset.csv > collect.log 2>&1 || fail "collect exited $?"
[ "$(rows dataset.csv)" -eq 12 ] || fail "dataset.csv has $(rows dataset.csv) rows, expected 12"
# The corners of each pose beside the dataset (issue 25), from the camera's H4_BOARD_CORNERS.
[ "$(head -1 dataset.corners.csv)" = "pose_id,tag_id,corner,u,v,sigma_px" ] \
  || fail "dataset.corners.csv: no corners header"
[ "$(corner_poses dataset.corners.csv)" -eq 12 ] \
  || fail "dataset.corners.csv has the corners of $(corner_poses dataset.corners.csv) poses, expected 12"
kill -INT $logger; wait $logger || true

# Interrupted (Ctrl-C: SIGINT) in the middle: exit 130, the rows so far flushed, and the
# same command resumes. Then killed (SIGKILL) further on, then started again: every pose
# exactly once.
"${collect[@]}" --out resumed.csv > interrupted.log 2>&1 &
victim=$!; pids+=($victim)
for _ in $(seq $((600 * scale))); do [ "$(rows resumed.csv)" -ge 2 ] && break; sleep 0.1; done
kill -INT $victim
status=0; wait $victim || status=$?
[ $status -eq 130 ] || fail "collect exited $status on SIGINT, expected 130"
interrupted=$(rows resumed.csv)
[ "$interrupted" -ge 2 ] && [ "$interrupted" -lt 12 ] || fail "SIGINT came at $interrupted rows"
grep -q "campaign: $interrupted of 12 planned poses in resumed.csv (0 from an earlier run), interrupted" \
  interrupted.log || fail "the summary on SIGINT does not match the $interrupted rows on disk"
grep -q "run the same command again to resume" interrupted.log || fail "no resume hint on SIGINT"
"${collect[@]}" --out resumed.csv > resumed_1.log 2>&1 &
victim=$!; pids+=($victim)
kill_at=$(( interrupted + 2 > 5 ? interrupted + 2 : 5 ))
for _ in $(seq $((600 * scale))); do [ "$(rows resumed.csv)" -ge $kill_at ] && break; sleep 0.1; done
kill -KILL $victim; wait $victim 2> /dev/null || true
# A row whose corners the interruption lost is measured again (issue 42, defect 6): the
# resume starts from the rows before it, and says so.
kept_rows() {  # ROWS LOG: the rows a resume keeps of ROWS
  local cut
  cut=$(sed -n 's/.*the corners of the last \([0-9]*\) poses recorded are not in.*/\1/p' "$2")
  echo $(( $1 - ${cut:-0} ))
}
grep -q "$(kept_rows "$interrupted" resumed_1.log) already in" resumed_1.log \
  || fail "the run after SIGINT did not resume from $interrupted rows"
before=$(rows resumed.csv)
[ "$before" -ge $kill_at ] && [ "$before" -lt 12 ] || fail "kill came at $before rows"
"${collect[@]}" --out resumed.csv > resumed_2.log 2>&1 || fail "resumed collect exited $?"
grep -q "$(kept_rows "$before" resumed_2.log) already in" resumed_2.log ||
  fail "the restart did not resume from $before rows"
[ "$(rows resumed.csv)" -eq 12 ] || fail "resumed.csv has $(rows resumed.csv) rows"
[ "$(cut -d, -f1 resumed.csv | tail -n +2 | sort -n | uniq | wc -l)" -eq 12 ] \
  || fail "resumed.csv does not hold 12 distinct poses"
# A resumed campaign writes each pose's corners once (a pose killed between its row and its
# corners is measured again).
[ "$(tail -n +2 resumed.corners.csv | cut -d, -f1,3 | sort | uniq -d | wc -l)" -eq 0 ] \
  || fail "resumed.corners.csv holds a corner of a pose twice"

kill -TERM $robot $camera
wait $robot || fail "sim-robot exited $? on SIGTERM"
wait $camera || fail "h4cam exited $? on SIGTERM"
pids=()

# Replays rebuild the same rows.
"$h4cal" collect --from-log campaign.lcmlog --plan plan.csv --out from_log.csv --auth-key h4.key \
  > from_log.log 2>&1 || fail "collect --from-log exited $?"
cmp dataset.csv from_log.csv || fail "--from-log rebuilt other rows"
cmp dataset.corners.csv from_log.corners.csv || fail "--from-log rebuilt other corners"
grep -q " 0 not authentic" from_log.log || fail "--from-log with the key dropped messages"
# collect --report-dir judges its results as identify does: a verdict for each model first,
# exit 3 when none is good (twelve poses are too few, below).
# Its results carry their provenance, and with --camera and --board its report maps the
# corners the campaign recorded (issue 43 point 5: neither did).
"$h4cal" collect --from-log campaign.lcmlog --plan plan.csv --out from_log_id.csv \
  --auth-key h4.key --report-dir identified --robot sim/robot.yaml \
  --camera "$src/boards/sim_camera_1024x768.yaml" \
  --board "$src/boards/aprilgrid_6x6_30mm.yaml" > from_log_id.log 2>&1 && status=0 || status=$?
[ $status -eq 3 ] || fail "collect --report-dir on 12 poses exited $status, expected 3"
[ "$(grep -c '^VERDICT: too_few_poses' from_log_id.log)" -eq 2 ] ||
  fail "collect --report-dir did not print both verdicts: $(grep -c VERDICT from_log_id.log)"
grep -q "^collect: no model's verdict is good" from_log_id.log || fail "no closing verdict line"
[ -s identified/report.html ] || fail "collect --report-dir wrote no report"
grep -q '"h4cal_version"' identified/result12.json || fail "collect's result has no provenance"
! grep -q "This result does not record which h4cal made it" identified/report.html ||
  fail "collect's report says its result has no provenance"
! grep -q "no corners given" identified/report.html ||
  fail "collect's report has no camera section though the campaign recorded corners"
"$h4cal" collect --passive --plan plan.csv --out passive.csv > passive.log 2>&1 &
listener=$!; pids+=($listener)
"$h4cal" collect --passive --plan plan.csv --out foreign.csv --auth-key other.key \
  > foreign.log 2>&1 &
foreign=$!; pids+=($foreign)
sleep 0.5
# Twice as fast as recorded. The sanitizer pass's log (2 frames per measurement, each
# rendered ~7x slower) is about as long as the optimised pass's, and no denser. At four times
# (400 joint states a second) a listener on a machine loaded by a build lost 144 of 3255 joint
# states at its UDP socket, a pose's settled reading among them, and rebuilt 11 rows of 12
# (twice in four runs this session); UDP multicast drops what a busy reader does not drain.
lcm-logplayer -s 2 campaign.lcmlog > logplayer.log 2>&1 || fail "lcm-logplayer exited $?"
for _ in $(seq $((100 * scale))); do kill -0 $listener 2> /dev/null || break; sleep 0.1; done
kill -INT $listener $foreign 2> /dev/null || true
wait $listener || true
wait $foreign || true
pids=()
cmp dataset.csv passive.csv || fail "lcm-logplayer into collect --passive rebuilt other rows"
[ "$(rows foreign.csv)" -eq 0 ] || fail "a listener with another key recorded $(rows foreign.csv) rows"
dropped=$(sed -nE 's/.* ([0-9]+) not authentic.*/\1/p' foreign.log)
[ "${dropped:-0}" -ge 12 ] || fail "the listener with another key dropped '${dropped}' messages, expected >= 12"

# The live dataset identifies the true robot. Twelve poses are fewer than the verdict asks
# for (20), so identify says so and exits 3; the fit itself must still hold.
"$h4cal" identify --robot sim/robot.yaml --data dataset.csv --model 12 --validation 0 \
  --out result12.json > identify.log 2>&1 && status=0 || status=$?
[ $status -eq 3 ] && grep -q "^VERDICT: too_few_poses" identify.log ||
  fail "identify on 12 poses exited $status, expected 3 with the verdict too_few_poses"
line=$("$h4cal" fk --result result12.json --joints sim/heldout_joints.csv --out fk.csv \
       --compare sim/heldout_truth.csv 2> /dev/null)
read -r p r <<< "$(echo "$line" | sed -E 's/.*position RMS ([0-9.]+) mm, rotation RMS ([0-9.]+) deg.*/\1 \2/')"
below "$p" 0.10 || fail "held-out position RMS $p mm > 0.10"
below "$r" 0.02 || fail "held-out rotation RMS $r deg > 0.02"
echo "PASS: 12 live poses -> held-out $p mm, $r deg; SIGINT at $interrupted rows (130), killed" \
  "at $before rows, resumed to 12;" \
  "--from-log and lcm-logplayer replays identical; all signed, another key dropped $dropped"

#!/usr/bin/env bash
# The command-line contract of `h4cal sim-robot` (the bus behaviour is tested in-process
# over memq://, which does not cross processes): help lists every option, a missing truth
# is a clear error, a bad truth path names the file, and a short run on a real truth file
# exits 0 after --duration.
set -uo pipefail
. "$(dirname "$0")/h4cal_test_lib.sh"

help=$("$h4cal" sim-robot --help 2>&1) || fail "--help exited non-zero: $help"
for option in --truth --robot --paper --robot-seed --joint-speed --settle-time --sigma-q \
              --joint-range-deg --seed --rate --status-period --lcm-url --duration; do
  grep -q -- "$option" <<< "$help" || fail "--help does not list $option"
done

out=$("$h4cal" sim-robot --duration 1 2>&1)
[ $? -ne 0 ] || fail "sim-robot without --truth or --paper exited 0"
echo "$out" | grep -q -- "--truth" || fail "missing truth not explained: $out"
echo "$out" | grep -q -- "--paper" || fail "missing truth not explained: $out"

out=$("$h4cal" sim-robot --truth "$dir/no_such_truth.yaml" --robot "$dir/x.yaml" --duration 1 2>&1)
[ $? -ne 0 ] || fail "sim-robot with a missing truth file exited 0"
echo "$out" | grep -q "no_such_truth.yaml" || fail "bad truth path not named: $out"

"$h4cal" simulate --truth 12 --out-dir "$dir/sim" 2>/dev/null || fail "simulate"
# Without --robot the a priori robot.yaml beside the truth is used; memq:// needs no network.
out=$("$h4cal" sim-robot --truth "$dir/sim/truth.yaml" --lcm-url memq:// --duration 0.5 2>&1)
[ $? -eq 0 ] || fail "a 0.5 s run exited non-zero: $out"
echo "$out" | grep -q "a priori $dir/sim/robot.yaml" || fail "a priori robot not reported: $out"
echo "$out" | grep -q "joint states" || fail "no status line: $out"

# No robot.yaml beside the truth and no --robot: an error naming the missing file.
mkdir -p "$dir/lonely"; cp "$dir/sim/truth.yaml" "$dir/lonely/"
out=$("$h4cal" sim-robot --truth "$dir/lonely/truth.yaml" --lcm-url memq:// --duration 0.5 2>&1)
[ $? -ne 0 ] || fail "sim-robot without an a priori robot exited 0"
echo "$out" | grep -q "lonely/robot.yaml" || fail "missing a priori robot not named: $out"

# SIGTERM stops it cleanly with exit 0, also when it comes early: the test once waited a
# fixed second, and on a loaded machine the signal arrived before the handler (exit 143).
"$h4cal" sim-robot --paper --lcm-url memq:// > "$dir/term.log" 2>&1 &
pid=$!
for _ in $(seq 300); do grep -q "sim-robot:" "$dir/term.log" && break; sleep 0.1; done
kill -TERM $pid
wait $pid
rc=$?
[ $rc -eq 0 ] || fail "SIGTERM exit code $rc: $(cat "$dir/term.log")"
grep -q "stopped after" "$dir/term.log" || fail "no stop line: $(cat "$dir/term.log")"
# On LCM's default group it says that every LCM program of the machine shares it and how to
# keep a rehearsal to itself (issue 43 point 6); on a group of its own, or memq://, not.
grep -q "default group" "$dir/term.log" && fail "memq:// warned of the default group"
netns=$(dirname "$0")/../../scripts/in-private-netns
if "$netns" --check > /dev/null 2>&1; then
  out=$(env -u LCM_DEFAULT_URL "$netns" "$h4cal" sim-robot --paper --duration 0.3 2>&1)
  echo "$out" | grep -q "on LCM's default group.*set LCM_DEFAULT_URL" ||
    fail "no warning on the default group: $out"
  out=$(LCM_DEFAULT_URL="udpm://239.255.76.99:7667?ttl=0" "$netns" "$h4cal" sim-robot --paper \
    --duration 0.3 2>&1)
  ! echo "$out" | grep -q "default group" || fail "warned on a group of its own: $out"
else
  echo "note: no private network namespace here, the default-group warning was not checked" >&2
fi
echo "PASS"

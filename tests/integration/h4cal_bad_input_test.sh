#!/usr/bin/env bash
# Bad input to h4cal gives a non-zero exit and a message naming the file, line and field.
set -uo pipefail
h4cal=$1
dir=$2
rm -rf "$dir"; mkdir -p "$dir"
fail() { echo "FAIL: $*" >&2; exit 1; }

"$h4cal" simulate --truth 12 --out-dir "$dir/sim" 2>/dev/null || fail "simulate"
# A non-unit quaternion on line 5 (the 4th data row).
awk -F, 'BEGIN{OFS=","} NR==5 {$10=0.5} {print}' "$dir/sim/dataset.csv" > "$dir/bad.csv"
out=$("$h4cal" identify --robot "$dir/sim/robot.yaml" --data "$dir/bad.csv" --out "$dir/r.json" 2>&1)
rc=$?
[ $rc -ne 0 ] || fail "identify accepted a non-unit quaternion"
echo "$out" | grep -q "bad.csv:5" || fail "message does not name bad.csv line 5: $out"
[ ! -e "$dir/r.json" ] || fail "a result was written for bad input"

# A duplicate pose id.
{ cat "$dir/sim/dataset.csv"; sed -n 2p "$dir/sim/dataset.csv"; } > "$dir/dup.csv"
out=$("$h4cal" identify --robot "$dir/sim/robot.yaml" --data "$dir/dup.csv" --out "$dir/r.json" 2>&1)
[ $? -ne 0 ] || fail "identify accepted a duplicate pose_id"
echo "$out" | grep -q "dup.csv:83.*pose_id" || fail "duplicate not named at line 83: $out"

# A result of the wrong model for --from.
"$h4cal" identify --robot "$dir/sim/robot.yaml" --data "$dir/sim/dataset.csv" --model 31 \
  --out "$dir/r31.json" > /dev/null 2>&1 || fail "identify 31"
out=$("$h4cal" identify --robot "$dir/sim/robot.yaml" --data "$dir/sim/dataset.csv" --model 31 \
  --from "$dir/r31.json" --out "$dir/r.json" 2>&1)
[ $? -ne 0 ] || fail "--from accepted a Model 31 result"
echo "$out" | grep -q "needs a Model 12 result" || fail "unclear --from message: $out"

# Unreachable joints in fk: reported, exit 3, no NaN written.
printf 'pose_id,q1,q2,q3,q4\n1,0,0,0,0\n' > "$dir/joints.csv"
"$h4cal" fk --robot "$dir/sim/robot.yaml" --joints "$dir/joints.csv" --out "$dir/fk.csv" > /dev/null 2>&1
rc=$?
[ $rc -eq 3 ] || fail "fk of impossible joints exited $rc, expected 3"
! grep -qi nan "$dir/fk.csv" || fail "fk wrote NaN"
echo "PASS"

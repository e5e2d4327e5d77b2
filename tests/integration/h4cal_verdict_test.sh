#!/usr/bin/env bash
# The verdict of `h4cal identify` on simulated campaigns (paper protocol, 81 poses): a
# normal campaign is "good" with exit 0; a robot.yaml in millimetres, swapped joint
# columns, Model 12 on a Model 31 robot and a 10-pose dataset each get their own verdict,
# printed first, in the result JSON, and exit code 3; a fit whose result the reader would
# refuse (decimetres, swapped joints) prints its verdict and writes no result, exit 1.
set -uo pipefail
. "$(dirname "$0")/h4cal_test_lib.sh"

# expect_verdict NAME CODE RC ROBOT DATA [identify options...]
# expect_unwritten NAME CODE ROBOT DATA: the verdict printed first, but a fit whose result
# h4cal's own reader refuses (a negative length) is not written: exit 1 (issue 42, defect 9).
expect_unwritten() {
  local name=$1 code=$2 robot=$3 data=$4
  "$h4cal" identify --robot "$robot" --data "$data" --out "$dir/$name.json" \
    > "$dir/$name.txt" 2> "$dir/$name.log"
  local rc=$?
  [ "$rc" -eq 1 ] || fail "$name: exit $rc, expected 1: $(head -3 "$dir/$name.txt")"
  head -1 "$dir/$name.txt" | grep -q "^VERDICT: $code\$" \
    || fail "$name: first line '$(head -1 "$dir/$name.txt")', expected VERDICT: $code"
  grep -q "$name.json: not written: the result cannot be trusted, h4cal's own reader refuses it" \
    "$dir/$name.log" || fail "$name: $(tail -1 "$dir/$name.log")"
  [ ! -e "$dir/$name.json" ] || fail "$name: a result its reader refuses was written"
  echo "$name: $(sed -n 2p "$dir/$name.txt")"
}

expect_verdict() {
  local name=$1 code=$2 rc_expected=$3 robot=$4 data=$5
  shift 5
  "$h4cal" identify --robot "$robot" --data "$data" --out "$dir/$name.json" "$@" \
    > "$dir/$name.txt" 2> "$dir/$name.log"
  local rc=$?
  [ "$rc" -eq "$rc_expected" ] || fail "$name: exit $rc, expected $rc_expected: $(head -3 "$dir/$name.txt")"
  head -1 "$dir/$name.txt" | grep -q "^VERDICT: $code\$" \
    || fail "$name: first line '$(head -1 "$dir/$name.txt")', expected VERDICT: $code"
  grep -q "\"code\": \"$code\"" "$dir/$name.json" || fail "$name: the JSON verdict is not $code"
  echo "$name: $(sed -n 2p "$dir/$name.txt")"
}

"$h4cal" simulate --truth 12 --seed 3 --robot-seed 3 --out-dir "$dir/m12" 2>/dev/null \
  || fail "simulate Model 12"
"$h4cal" simulate --truth 31 --seed 4 --robot-seed 4 --out-dir "$dir/m31" 2>/dev/null \
  || fail "simulate Model 31"

expect_verdict good good 0 "$dir/m12/robot.yaml" "$dir/m12/dataset.csv" --model 12
grep -q '"h4cal_version"' "$dir/good.json" || fail "no provenance in the result"
grep -q "\"$dir/m12/dataset.csv\"" "$dir/good.json" || fail "the input files are not recorded"

expect_verdict model12_on_31 model_cannot_describe 3 "$dir/m31/robot.yaml" "$dir/m31/dataset.csv" \
  --model 12
grep -q "Use Model 31" "$dir/model12_on_31.txt" || fail "model12_on_31: the text does not say use Model 31"

# robot.yaml written in millimetres for the arm.
sed -E 's/^(  arm: )([0-9.]+)/echo "\1$(awk "BEGIN{print \2*1000}")"/e' "$dir/m12/robot.yaml" \
  > "$dir/robot_mm.yaml"
grep -q '^  arm: 260' "$dir/robot_mm.yaml" || fail "robot_mm.yaml: $(grep arm "$dir/robot_mm.yaml")"
# 260 m is past the reader's bound (no part of an H4 lies 10 m from its base): refused
# before any work, naming the field.
"$h4cal" identify --robot "$dir/robot_mm.yaml" --data "$dir/m12/dataset.csv" \
  --out "$dir/millimetres.json" > /dev/null 2> "$dir/millimetres.log"
rc=$?
[ $rc -eq 1 ] || fail "millimetres: exit $rc, expected 1"
grep -q "field 'model12.arm': expected a length within 10 m, got 260" "$dir/millimetres.log" \
  || fail "millimetres: $(cat "$dir/millimetres.log")"
# The arm ten times too long (a unit slip within the bound) reads, and the verdict says the
# a priori is wrong. Its fit ends with a negative arm, which h4cal's reader refuses: the
# result is not written, exit 1, after the verdict.
sed -E 's/^(  arm: )([0-9.]+)/echo "\1$(awk "BEGIN{print \2*10}")"/e' "$dir/m12/robot.yaml" \
  > "$dir/robot_dm.yaml"
grep -q '^  arm: 2.6' "$dir/robot_dm.yaml" || fail "robot_dm.yaml: $(grep arm "$dir/robot_dm.yaml")"
expect_unwritten decimetres inconsistent_with_apriori "$dir/robot_dm.yaml" "$dir/m12/dataset.csv"

# Joint columns q1 and q2 swapped (a controller reporting its joints in another order).
awk -F, 'BEGIN{OFS=","} NR > 1 {t=$3; $3=$4; $4=t} {print}' "$dir/m12/dataset.csv" > "$dir/swapped.csv"
expect_unwritten swapped_joints inconsistent_with_apriori "$dir/m12/robot.yaml" "$dir/swapped.csv"

# Ten poses: the header and the first ten rows, no held-out split.
head -11 "$dir/m12/dataset.csv" | sed -E 's/,valid(,|$)/,calib\1/' > "$dir/ten.csv"
expect_verdict ten_poses too_few_poses 3 "$dir/m12/robot.yaml" "$dir/ten.csv"
echo "PASS"

#!/usr/bin/env bash
# The user's path through h4cal on simulated data: simulate -> identify (12, then 31 from
# 12) -> fk of the held-out true joints -> compared with the true board poses. Asserts
# the accuracy targets of issue "Host solver" on the paper's protocol (71 + 10 poses,
# 0.2 mm / 0.03 deg camera noise): Model 12 data with Model 12 <= 0.10 mm / 0.02 deg;
# Model 31 data with Model 31 <= 0.20 mm / 0.04 deg and Model 12 clearly worse.
set -euo pipefail
. "$(dirname "$0")/h4cal_test_lib.sh"

# score RESULT DIR -> "position_mm rotation_deg"
score() {
  local line
  line=$("$h4cal" fk --result "$1" --joints "$2/heldout_joints.csv" --out "$2/fk.csv" \
         --compare "$2/heldout_truth.csv" 2>/dev/null)
  echo "$line" >&2
  echo "$line" | sed -E 's/.*position RMS ([0-9.]+) mm, rotation RMS ([0-9.]+) deg.*/\1 \2/'
}
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'; }

# Model 12 truth.
"$h4cal" simulate --truth 12 --seed 3 --robot-seed 3 --out-dir "$dir/m12" 2>/dev/null
[ "$(wc -l < "$dir/m12/dataset.csv")" -eq 82 ] || fail "dataset should have 81 rows + header"
"$h4cal" identify --robot "$dir/m12/robot.yaml" --data "$dir/m12/dataset.csv" --model 12 \
  --out "$dir/m12/result12.json" > "$dir/m12/identify.txt" 2>&1 || fail "identify 12 exited $?"
grep -q '"model": "12"' "$dir/m12/result12.json" || fail "result JSON lacks model 12"
read -r p r <<< "$(score "$dir/m12/result12.json" "$dir/m12")"
below "$p" 0.10 || fail "Model 12: position RMS $p mm > 0.10"
below "$r" 0.02 || fail "Model 12: rotation RMS $r deg > 0.02"

# Issue 42, defect 8: fk and ik of a Model 31 result worked in B31, not in B as the poses
# and joints CSVs say (an ik target landed 140 mm away). Model 31 from Model 12 on this
# Model 12 robot: both describe it, so both put the held-out joints at the same pose in B,
# and ik of those poses gives back the joints. Up to the frames' own difference: Model 31's
# B31 sits at its identified joint 1, B at the a priori's nominal map of it, a few mm apart
# (the robot's departure from its a priori); in B31 they were 140 mm apart.
"$h4cal" identify --robot "$dir/m12/robot.yaml" --data "$dir/m12/dataset.csv" --model 31 \
  --from "$dir/m12/result12.json" --out "$dir/m12/result31.json" > /dev/null 2>&1 && rc=0 || rc=$?
[ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] || fail "identify 31 --from on Model 12 data exited $rc"
for m in 12 31; do
  "$h4cal" fk --result "$dir/m12/result$m.json" --joints "$dir/m12/heldout_joints.csv" \
    --out "$dir/m12/fk_b$m.csv" > "$dir/m12/fk_b$m.txt" 2>&1 || fail "fk Model $m: $(tail -1 "$dir/m12/fk_b$m.txt")"
done
grep -q "end-effector poses in B" "$dir/m12/fk_b31.txt" || fail "fk does not say the frame: $(cat "$dir/m12/fk_b31.txt")"
far=$(awk -F, 'NR == FNR { if (FNR > 1) p[$1] = $2 " " $3 " " $4; next }
  FNR > 1 { split(p[$1], a, " "); d = sqrt(($2 - a[1])^2 + ($3 - a[2])^2 + ($4 - a[3])^2)
            if (d > m) m = d } END { printf "%.6f", m * 1e3 }' "$dir/m12/fk_b12.csv" "$dir/m12/fk_b31.csv")
below "$far" 10.0 || fail "fk: Model 31 puts the held-out joints $far mm from Model 12's pose in B"
cut -d, -f1-5 "$dir/m12/fk_b12.csv" > "$dir/m12/poses_b.csv"
"$h4cal" ik --result "$dir/m12/result31.json" --poses "$dir/m12/poses_b.csv" \
  --out "$dir/m12/ik31.csv" > "$dir/m12/ik31.txt" 2>&1 || fail "ik Model 31: $(tail -1 "$dir/m12/ik31.txt")"
off=$(awk -F, 'NR == FNR { if (FNR > 1) for (i = 2; i <= 5; i++) q[$1, i] = $i; next }
  FNR > 1 { for (i = 2; i <= 5; i++) { d = $i - q[$1, i]; if (d < 0) d = -d; if (d > 3.14159) d = 6.28319 - d
            if (d > m) m = d } } END { printf "%.6f", m }' "$dir/m12/heldout_joints.csv" "$dir/m12/ik31.csv")
below "$off" 0.05 || fail "ik: Model 31 gives joints $off rad from the held-out ones for their poses in B"

# Model 31 truth.
"$h4cal" simulate --truth 31 --seed 4 --robot-seed 4 --out-dir "$dir/m31" 2>/dev/null
# Model 12 cannot describe a Model 31 robot: its verdict says so, exit 3 (the result is
# still written, and Model 31 starts from it).
"$h4cal" identify --robot "$dir/m31/robot.yaml" --data "$dir/m31/dataset.csv" --model 12 \
  --out "$dir/m31/result12.json" > /dev/null 2>&1 && rc=0 || rc=$?
[ "$rc" -eq 3 ] || fail "identify 12 on Model 31 data exited $rc, expected 3 (model cannot describe)"
"$h4cal" identify --robot "$dir/m31/robot.yaml" --data "$dir/m31/dataset.csv" --model 31 \
  --from "$dir/m31/result12.json" --out "$dir/m31/result31.json" > /dev/null 2>&1 \
  || fail "identify 31 --from"
read -r p31 r31 <<< "$(score "$dir/m31/result31.json" "$dir/m31")"
read -r p12 r12 <<< "$(score "$dir/m31/result12.json" "$dir/m31")"
below "$p31" 0.20 || fail "Model 31: position RMS $p31 mm > 0.20"
below "$r31" 0.04 || fail "Model 31: rotation RMS $r31 deg > 0.04"
# "Clearly worse": at least three times the Model 31 error.
below "$(awk -v a="$p31" 'BEGIN{print 3*a}')" "$p12" || fail "Model 12 ($p12 mm) not clearly worse than 31 ($p31 mm)"
echo "PASS: m12 $p mm $r deg; m31 $p31 mm $r31 deg; m12-on-31 $p12 mm"

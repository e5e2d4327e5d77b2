#!/usr/bin/env bash
# Bad input to h4cal gives a non-zero exit and a message naming the file, line and field.
set -uo pipefail
. "$(dirname "$0")/h4cal_test_lib.sh"

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

# --- Regressions: crashes, hangs, data loss and silent errors on files and options. -------------
# `expect_error NAME PATTERN CMD...`: CMD exits 1 (an error, not a crash: 134/139 are
# signals, 124 a hang stopped by timeout) and its message matches PATTERN.
expect_error() {
  local name=$1 pattern=$2
  shift 2
  local out rc
  out=$(timeout 60 "$@" 2>&1)
  rc=$?
  [ $rc -eq 1 ] || fail "$name: exit code $rc, expected 1 (error): $out"
  echo "$out" | grep -q -- "$pattern" || fail "$name: message does not match '$pattern': $out"
}
robot="$dir/sim/robot.yaml"

# Datasets with no calibration row: header only, CR-only line ends, a set column of only
# 'valid', and simulate's output with every pose held out.
head -1 "$dir/sim/dataset.csv" > "$dir/header_only.csv"
expect_error "header-only dataset" "header_only.csv: identification needs at least 3 calibration" \
  "$h4cal" identify --robot "$robot" --data "$dir/header_only.csv" --out "$dir/r.json"
tr '\n' '\r' < "$dir/sim/dataset.csv" > "$dir/cr_only.csv"
expect_error "CR-only line ends" "cr_only.csv:1: a carriage return inside a line" \
  "$h4cal" identify --robot "$robot" --data "$dir/cr_only.csv" --out "$dir/r.json"
# simulate's columns: pose_id,utime,q1..q4,x,y,z,qw,qx,qy,qz,set,sigma_t,sigma_r
head -1 "$dir/sim/dataset.csv" | grep -q ',qz,set,sigma_t,sigma_r$' || fail "simulate's columns changed"
awk -F, 'BEGIN{OFS=","} NR>1 {$14="valid"} {print}' "$dir/sim/dataset.csv" > "$dir/all_valid.csv"
expect_error "set column of only valid" "all_valid.csv: identification needs at least 3" \
  "$h4cal" identify --robot "$robot" --data "$dir/all_valid.csv" --out "$dir/r.json"
"$h4cal" simulate --truth 12 --validation 81 --out-dir "$dir/sim81" > /dev/null 2>&1 ||
  fail "simulate --validation 81"
expect_error "simulate --validation 81 output" "identification needs at least 3 calibration" \
  "$h4cal" identify --robot "$dir/sim81/robot.yaml" --data "$dir/sim81/dataset.csv" \
  --out "$dir/r.json"
expect_error "simulate --validation above the plan" "--validation 1000: only 81 poses" \
  "$h4cal" simulate --truth 12 --validation 1000 --out-dir "$dir/sim1000"
[ ! -e "$dir/r.json" ] || fail "a result was written for a dataset without calibration rows"

# --validation above half the dataset is an error, not a silent 40.
cut -d, -f1-13 "$dir/sim/dataset.csv" > "$dir/no_set.csv"
expect_error "--validation 1000" "--validation 1000: at most half of the 81 poses" \
  "$h4cal" identify --robot "$robot" --data "$dir/no_set.csv" --validation 1000 --out "$dir/r.json"

# --fix: a typo is an error listing the parameters; all twelve placement parameters fixed
# is a valid (if poor) identification, not a crash.
expect_error "--fix typo" "cannot fix 'X_BC.tq'.*X_BC.tx" \
  "$h4cal" identify --robot "$robot" --data "$dir/sim/dataset.csv" --fix X_BC.tq --out "$dir/r.json"
placement=X_BC.tx,X_BC.ty,X_BC.tz,X_BC.rx,X_BC.ry,X_BC.rz,X_TE.tx,X_TE.ty,X_TE.tz,X_TE.rx,X_TE.ry,X_TE.rz
out=$(timeout 120 "$h4cal" identify --robot "$robot" --data "$dir/sim/dataset.csv" \
  --fix "$placement" --out "$dir/fixed12.json" 2>&1)
rc=$?
[ $rc -eq 0 ] || [ $rc -eq 3 ] || fail "identify --fix of all of X_BC, X_TE exited $rc: $out"
[ -s "$dir/fixed12.json" ] || fail "identify --fix of all of X_BC, X_TE wrote no result"

# A sigma too small to weigh (1/sigma^2 overflows): refused at load, naming line and field.
awk -F, 'BEGIN{OFS=","} NR==3 {$15="1e-160"} {print}' "$dir/sim/dataset.csv" > "$dir/tiny_sigma.csv"
expect_error "sigma 1e-160" "tiny_sigma.csv:3: field 'sigma_t': expected a standard deviation in" \
  "$h4cal" identify --robot "$robot" --data "$dir/tiny_sigma.csv" --out "$dir/r.json"

# JSON nested 100,000 deep: an error naming the file, never a stack overflow.
{ head -c 100000 /dev/zero | tr '\0' '['; head -c 100000 /dev/zero | tr '\0' ']'; } > "$dir/deep.json"
for cmd in fk ik export; do
  case $cmd in
    fk) args=(--joints "$dir/joints.csv" --out "$dir/deep_out.csv") ;;
    ik) printf 'pose_id,X,Y,Z,theta\n1,0,0,-0.45,0\n' > "$dir/poses.csv"
        args=(--poses "$dir/poses.csv" --out "$dir/deep_out.csv") ;;
    export) args=(--out "$dir/deep_out.yaml") ;;
  esac
  expect_error "$cmd on deep JSON" "deep.json:1: JSON nested deeper than 64 levels" \
    "$h4cal" "$cmd" --result "$dir/deep.json" "${args[@]}"
done
expect_error "identify --from deep JSON" "deep.json:1: JSON nested deeper than 64" \
  "$h4cal" identify --robot "$robot" --data "$dir/sim/dataset.csv" --model 31 \
  --from "$dir/deep.json" --out "$dir/r.json"
"$h4cal" identify --robot "$robot" --data "$dir/sim/dataset.csv" --out "$dir/r12.json" \
  > /dev/null 2>&1 || fail "identify 12"
mkdir -p "$dir/sim_deep" && cp -r "$dir/sim/"* "$dir/sim_deep/" && cp "$dir/deep.json" "$dir/sim_deep/result12.json"
expect_error "validate on deep JSON" "result12.json:1: JSON nested deeper than 64" \
  "$h4cal" validate --sim-dir "$dir/sim_deep"

# An output that is an input is refused, by path, through a hard link, and the file is kept.
cp "$dir/sim/dataset.csv" "$dir/keep.csv"
sum_before=$(md5sum < "$dir/keep.csv")
expect_error "--out equal to --data" "--out .*keep.csv is the same file as --data" \
  "$h4cal" identify --robot "$robot" --data "$dir/keep.csv" --out "$dir/keep.csv"
ln -f "$dir/keep.csv" "$dir/keep_link.csv"
expect_error "--out a hard link of --data" "is the same file as --data" \
  "$h4cal" identify --robot "$robot" --data "$dir/keep.csv" --out "$dir/keep_link.csv"
expect_error "fk --out equal to --joints" "is the same file as --joints" \
  "$h4cal" fk --robot "$robot" --joints "$dir/joints.csv" --out "$dir/./joints.csv"
[ "$(md5sum < "$dir/keep.csv")" = "$sum_before" ] || fail "the dataset was overwritten"

# A failed write (file size limit: the write fails with EFBIG) keeps the previous result.
cp "$dir/r12.json" "$dir/previous.json"
(trap '' XFSZ; ulimit -f 4; "$h4cal" identify --robot "$robot" --data "$dir/sim/dataset.csv" \
  --out "$dir/r12.json" > "$dir/efbig.log" 2>&1)
rc=$?
[ $rc -eq 1 ] || fail "identify with a failing write exited $rc: $(cat "$dir/efbig.log")"
cmp -s "$dir/r12.json" "$dir/previous.json" || fail "a failed write changed the previous result"
! ls -a "$dir" | grep -q '\.tmp-' || fail "a temporary file was left behind"

# A result with a negative arm length is refused by ik and export, naming the field.
sed '/"name": "arm",/{n;s/"value": /"value": -/}' "$dir/r12.json" > "$dir/negative_arm.json"
grep -q '"value": -0\.' "$dir/negative_arm.json" || fail "the negative arm was not written"
expect_error "ik with a negative arm" "negative_arm.json: field 'parameters\[1\].value': expected a positive length" \
  "$h4cal" ik --result "$dir/negative_arm.json" --poses "$dir/poses.csv" --out "$dir/j.csv"
expect_error "export with a negative arm" "field 'parameters\[1\].value': expected a positive length" \
  "$h4cal" export --result "$dir/negative_arm.json" --out "$dir/c.yaml"

# ik poses out of range: theta in degrees by mistake, an absurd position.
printf 'pose_id,X,Y,Z,theta\n1,0,0,-0.45,20\n' > "$dir/theta_deg.csv"
expect_error "ik theta 20" "theta_deg.csv:2: field 'theta': expected |theta| <= " \
  "$h4cal" ik --robot "$robot" --poses "$dir/theta_deg.csv" --out "$dir/j.csv"
printf 'pose_id,X,Y,Z,theta\n1,1e308,0,-0.45,0\n' > "$dir/huge.csv"
expect_error "ik X 1e308" "huge.csv:2: field 'X'" \
  "$h4cal" ik --robot "$robot" --poses "$dir/huge.csv" --out "$dir/j.csv"

# fk --robot on a Model 31 export uses its model31 block, never the a priori model12 block
# beside it: the same poses as fk of the result itself (to the export's digits).
"$h4cal" identify --robot "$robot" --data "$dir/sim/dataset.csv" --model 31 \
  --from "$dir/r12.json" --out "$dir/r31from12.json" > /dev/null 2>&1 || fail "identify 31 --from"
"$h4cal" export --result "$dir/r31from12.json" --robot "$robot" --out "$dir/c31.yaml" \
  > /dev/null 2>&1 || fail "export 31"
python3 - "$dir/sim/dataset.csv" "$dir/joints31.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))[:5]
with open(sys.argv[2], "w") as out:
    out.write("pose_id,q1,q2,q3,q4\n")
    for r in rows:
        out.write(",".join([r["pose_id"], r["q1"], r["q2"], r["q3"], r["q4"]]) + "\n")
PY
"$h4cal" fk --robot "$dir/c31.yaml" --joints "$dir/joints31.csv" --out "$dir/fk31_export.csv" \
  > /dev/null 2>&1 || fail "fk --robot on a Model 31 export"
# Assembly signs come from --robot beside --result, as in export and check (issue 26: one way
# to give them); --assembly-from is the old spelling and gives the same.
"$h4cal" fk --result "$dir/r31from12.json" --robot "$robot" --joints "$dir/joints31.csv" \
  --out "$dir/fk31_result.csv" > /dev/null 2>&1 || fail "fk --result of Model 31 with --robot"
"$h4cal" fk --result "$dir/r31from12.json" --assembly-from "$robot" --joints "$dir/joints31.csv" \
  --out "$dir/fk31_old.csv" > /dev/null 2>&1 || fail "fk --result --assembly-from"
cmp -s "$dir/fk31_result.csv" "$dir/fk31_old.csv" || fail "fk --robot and --assembly-from differ"
"$h4cal" fk --help | grep -q -- "--assembly-from" && fail "fk --help still shows --assembly-from"
python3 - "$dir/fk31_export.csv" "$dir/fk31_result.csv" <<'PY' || fail "fk of a Model 31 export differs from fk of its result"
import csv, sys
a, b = (list(csv.DictReader(open(p))) for p in sys.argv[1:3])
assert len(a) == len(b) == 5, (len(a), len(b))
for ra, rb in zip(a, b):
    for key in ("X", "Y", "Z"):
        assert abs(float(ra[key]) - float(rb[key])) < 1e-9, (key, ra, rb)
PY

# Authenticated messages: a key file group or others can read, or a short one, is refused
# naming the file, before any dataset is made.
head -c 32 /dev/urandom > "$dir/open.key"; chmod 644 "$dir/open.key"
expect_error "collect --auth-key mode 644" "open.key: auth key: mode 0644" \
  "$h4cal" collect --out "$dir/c.csv" --lcm-url memq:// --auth-key "$dir/open.key"
(umask 077; head -c 16 /dev/urandom > "$dir/short.key")
expect_error "collect --auth-key of 16 bytes" "short.key: auth key: 16 bytes; expected 32" \
  "$h4cal" collect --out "$dir/c.csv" --lcm-url memq:// --auth-key "$dir/short.key"
[ ! -e "$dir/c.csv" ] || fail "collect made a dataset with a refused key"
# A sequential campaign (issue 29): counts out of order, and what it plans for missing.
boards=$(cd "$(dirname "$0")/../../boards" && pwd)
expect_error "collect --sequential 20,10" "FIRST 20 >= TOTAL 10" \
  "$h4cal" collect --out "$dir/c.csv" --lcm-url memq:// --sequential 20,10 --robot "$robot" \
  --camera "$boards/sim_camera_1024x768.yaml" --board "$boards/aprilgrid_6x6_30mm.yaml"
expect_error "collect --sequential without --camera" "give --robot, --camera and --board" \
  "$h4cal" collect --out "$dir/c.csv" --lcm-url memq:// --sequential 12,24 --robot "$robot"
expect_error "collect --sequential with --plan" "not with --plan" \
  "$h4cal" collect --out "$dir/c.csv" --lcm-url memq:// --sequential 12,24 --robot "$robot" \
  --camera "$boards/sim_camera_1024x768.yaml" --board "$boards/aprilgrid_6x6_30mm.yaml" \
  --plan "$dir/sim/heldout_truth.csv"
[ ! -e "$dir/c.csv" ] || fail "collect made a dataset with refused --sequential options"
# Issue 27 point 4: plan accepted one pose (exit 0, "inf mm" predicted for 40 free
# parameters) and boards h4cam cannot measure (a family it does not detect, ids past the
# family's codes).
plan_inputs=(--robot "$robot" --camera "$boards/sim_camera_1024x768.yaml" --step 0.1)
expect_error "plan --count 1" "1 poses are too few: Model 31 needs at least 20" \
  "$h4cal" plan "${plan_inputs[@]}" --board "$boards/aprilgrid_6x6_30mm.yaml" --count 1 \
  --out "$dir/plan1.csv"
[ ! -e "$dir/plan1.csv" ] || fail "plan wrote a plan of one pose"
# ... while the 5 poses of a check campaign (issue 26: the walkthrough's check plan) are
# planned with --for-check: 5 rows, and the refusal above names nothing else.
"$h4cal" plan "${plan_inputs[@]}" --board "$boards/aprilgrid_6x6_30mm.yaml" --count 5 \
  --for-check --out "$dir/check5.csv" > "$dir/check5.log" 2>&1 || fail "plan --for-check: $(tail -2 "$dir/check5.log")"
[ "$(($(wc -l < "$dir/check5.csv") - 1))" -eq 5 ] || fail "plan --for-check did not write 5 poses"
grep -q "for h4cal check" "$dir/check5.log" || fail "plan --for-check did not say what the poses are for"
# ... within the region the grid calibrated (box 200 x 200 x 150 mm at z -0.45 m, theta within
# +-20 deg): beyond it the result extrapolates and an unchanged robot failed check.
awk -F, 'NR > 1 && ($2 < -0.1 || $2 > 0.1 || $3 < -0.1 || $3 > 0.1 || $4 < -0.525 ||
         $4 > -0.375 || $5 < -0.3491 || $5 > 0.3491) { print; bad = 1 } END { exit bad }' \
  "$dir/check5.csv" || fail "plan --for-check chose poses outside the calibrated region"
sed 's/^tagFamily: .*/tagFamily: tagCircle21h7/' "$boards/aprilgrid_6x6_30mm.yaml" > "$dir/circle.yaml"
expect_error "plan on tagCircle21h7" "circle.yaml:.*tagCircle21h7.*families h4cam detects" \
  "$h4cal" plan "${plan_inputs[@]}" --board "$dir/circle.yaml" --out "$dir/plan.csv"
sed 's/^firstId: .*/firstId: 560/' "$boards/aprilgrid_6x6_30mm.yaml" > "$dir/past_ids.yaml"
expect_error "plan on ids past tag36h11" "past_ids.yaml:.*past the 587 codes of tag36h11" \
  "$h4cal" plan "${plan_inputs[@]}" --board "$dir/past_ids.yaml" --out "$dir/plan.csv"
# Issue 42 point 3: --data, --robot and --corners naming a FIFO hung forever (and /dev/zero
# was read until the memory ran out): refused at once as not regular files. 10 s each at
# most, so that a regression fails here instead of hanging.
mkfifo "$dir/fifo.csv" "$dir/fifo.yaml"
expect_fifo_refused() {
  local name=$1 pattern=$2 out rc
  shift 2
  out=$(timeout 10 "$@" 2>&1)
  rc=$?
  [ $rc -eq 1 ] || fail "$name: exit code $rc, expected 1 (124: it waited on the FIFO): $out"
  echo "$out" | grep -q -- "$pattern" || fail "$name: message does not match '$pattern': $out"
}
expect_fifo_refused "--data FIFO" "fifo.csv: not a regular file (a FIFO)" \
  "$h4cal" identify --robot "$robot" --data "$dir/fifo.csv" --out "$dir/r.json"
expect_fifo_refused "--robot FIFO" "fifo.yaml: not a regular file (a FIFO)" \
  "$h4cal" identify --robot "$dir/fifo.yaml" --data "$dir/sim/dataset.csv" --out "$dir/r.json"
expect_fifo_refused "--data /dev/null" "/dev/null: not a regular file (a character device)" \
  "$h4cal" identify --robot "$robot" --data /dev/null --out "$dir/r.json"
expect_fifo_refused "--corners FIFO" "fifo.csv: not a regular file (a FIFO)" \
  "$h4cal" identify --robot "$robot" --data "$dir/sim/dataset.csv" --model 12 --folds 0 \
  --corners "$dir/fifo.csv" --board "$boards/aprilgrid_6x6_30mm.yaml" \
  --camera "$boards/sim_camera_1024x768.yaml" --out "$dir/r.json"
echo "PASS"

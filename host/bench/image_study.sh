#!/usr/bin/env bash
# The image study (docs/results.md#a-real-cameras-pixels-the-image-study): the whole chain a user
# runs, on board images instead of simulated corners. For each robot (a Model 31 robot drawn by
# `h4cal simulate --truth-model 31`, the paper's 81 grid poses, encoder noise) the board is
# rendered at each true pose through the TRUE camera (boards/sim_camera_1024x768.yaml) with an
# image formation, 10 frames per pose (`h4cam render`), measured by `h4cam measure --frames 10
# --corners-out` with a camera FILE (the exact one, or the typical-error one, as wrong as an
# ordinary intrinsic calibration), then identified by `h4cal identify`: the pose path (Model 12,
# then 31 --from it, with the file's covariance) and the corner path (--corners from the pose
# path's Model 31). Each result is scored where the true robot goes (h4_true_accuracy).
#   host/bench/image_study.sh BUILD_DIR OUT_DIR [--robots N] [--first-seed S]
#                            [--conditions "NAME ..."] [--files "exact typical"] [--frames F]
#                            [--corner-args "ARGS"] (more `identify --corners` options, e.g.
#                            --no-weigh-encoder-noise)
# Conditions (h4cam render options): linear (0.7 px optical blur, linear response), gamma
# (gamma 0.7, 1.4 px blur, 20 % gradient, 15 % vignetting, shot noise: an ISP's encoded
# output), pixelblur (linear, no optical blur, 0.7 px of blur of the pixel values after they
# integrated the light, as a renderer that blurs its pixels does), processed (the renderer's `processed` preset: sRGB, defocus).
# Prints one line per (robot, condition, file, path) and keeps every file under OUT_DIR.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
[ $# -ge 2 ] || { sed -n '2,16p' "$0" >&2; exit 2; }
build=$(cd "$1" && pwd) out=$2
shift 2
robots=3 first_seed=1 frames=10 corner_args=
conditions="linear gamma" files="exact typical"
while [ $# -gt 0 ]; do
  case "$1" in
    --robots) robots=$2; shift ;;
    --first-seed) first_seed=$2; shift ;;
    --conditions) conditions=$2; shift ;;
    --files) files=$2; shift ;;
    --frames) frames=$2; shift ;;
    --corner-args) corner_args=$2; shift ;;
    *) echo "image_study: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done
h4cam=$build/firmware/h4cam h4cal=$build/host/h4cal score=$build/host/bench/h4_true_accuracy
board=$root/boards/aprilgrid_6x6_30mm.yaml
true_camera=$root/boards/sim_camera_1024x768.yaml
mkdir -p "$out"

render_options() {  # condition
  case "$1" in
    linear) echo "--preset clean --blur-px 0.7" ;;
    gamma) echo "--preset clean --blur-px 1.4 --response gamma:0.7 --gradient 0.2 --vignetting 0.15 --full-well 6000 --read-noise 1" ;;
    pixelblur) echo "--preset clean --blur-px 0 --pixel-blur-px 0.7" ;;
    processed) echo "--preset processed" ;;
    *) echo "image_study: unknown condition '$1'" >&2; exit 2 ;;
  esac
}
camera_file() {  # exact|typical
  case "$1" in
    exact) echo "$true_camera" ;;
    typical) echo "$root/boards/sim_camera_1024x768_typical_error.yaml" ;;
    *) echo "image_study: unknown camera file '$1'" >&2; exit 2 ;;
  esac
}

# The dataset with each row's X_CT (and sigmas) replaced by h4cam's measurement of the same
# row (the measure CSV's row k is the dataset's row k); rows without a board are left out.
pair_measurements() {  # dataset.csv measured.csv out.csv
  python3 - "$@" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
measured = list(csv.DictReader(open(sys.argv[2])))
fields = list(rows[0].keys()) + [f for f in ("sigma_t", "sigma_r") if f not in rows[0]]
with open(sys.argv[3], "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    for row, m in zip(rows, measured):
        if not m["x"]:
            continue
        for k in ("x", "y", "z", "qw", "qx", "qy", "qz", "sigma_t", "sigma_r"):
            row[k] = m[k]
        w.writerow(row)
PY
}
# The corners CSV with pose_id the dataset's pose_id of the row instead of the row number.
renumber_corners() {  # dataset.csv corners.csv out.csv
  python3 - "$@" <<'PY'
import csv, sys
ids = [r["pose_id"] for r in csv.DictReader(open(sys.argv[1]))]
reader = csv.DictReader(open(sys.argv[2]))
with open(sys.argv[3], "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=reader.fieldnames, lineterminator="\n")
    w.writeheader()
    for r in reader:
        r["pose_id"] = ids[int(r["pose_id"])]
        w.writerow(r)
PY
}

identify() {  # dir dataset camera_file corners
  local dir=$1 data=$2 file=$3 corners=$4 rc
  local common=(--robot "$sim/robot.yaml" --data "$data" --board "$board" --camera "$file")
  rc=0; "$h4cal" identify "${common[@]}" --model 12 --out "$dir/result12.json" > "$dir/identify12.txt" 2>&1 || rc=$?
  [ $rc -le 3 ] || { echo "identify Model 12 failed (exit $rc), see $dir/identify12.txt" >&2; return 1; }
  rc=0; "$h4cal" identify "${common[@]}" --model 31 --from "$dir/result12.json" \
    --out "$dir/result31_pose_path.json" > "$dir/identify31.txt" 2>&1 || rc=$?
  [ $rc -le 3 ] || { echo "identify Model 31 failed (exit $rc), see $dir/identify31.txt" >&2; return 1; }
  rc=0; "$h4cal" identify "${common[@]}" --model 31 --from "$dir/result12.json" \
    --corners "$corners" $corner_args --out "$dir/result31_corners.json" \
    > "$dir/identify_corners.txt" 2>&1 || rc=$?
  [ $rc -le 3 ] || { echo "the corner path failed (exit $rc), see $dir/identify_corners.txt" >&2; return 1; }
}

for ((seed = first_seed; seed < first_seed + robots; ++seed)); do
  sim=$out/robot$seed/sim
  # Exact board poses (no pose noise): the poses the renderer images.
  "$h4cal" simulate --truth-model 31 --robot-seed "$seed" --seed "$seed" \
    --sigma-t-mm 0 --sigma-r-deg 0 --out-dir "$sim" > /dev/null
  for condition in $conditions; do
    images=$out/robot$seed/$condition/images
    read -r -a options <<< "$(render_options "$condition")"
    if [ ! -f "$images/done" ]; then
      mkdir -p "$images"
      python3 -c '
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    print(r["x"], r["y"], r["z"], r["qw"], r["qx"], r["qy"], r["qz"])' "$sim/dataset.csv" |
      { k=0; while read -r -a pose; do
          "$h4cam" render --board "$board" --camera "$true_camera" --pose "${pose[@]}" \
            "${options[@]}" --frames "$frames" --seed $((1000 * seed + k)) \
            --out-dir "$images/$(printf %03d $k)" > /dev/null
          k=$((k + 1))
        done; }
      touch "$images/done"
    fi
    for file in $files; do
      dir=$out/robot$seed/$condition/$file
      mkdir -p "$dir"
      "$h4cam" measure --board "$board" --camera "$(camera_file "$file")" --frames "$frames" \
        --out "$dir/measured.csv" --corners-out "$dir/corners_by_row.csv" \
        "$images"/*/frame_*.png > "$dir/measure.txt" 2>&1
      pair_measurements "$sim/dataset.csv" "$dir/measured.csv" "$dir/dataset.csv"
      renumber_corners "$sim/dataset.csv" "$dir/corners_by_row.csv" "$dir/corners.csv"
      identify "$dir" "$dir/dataset.csv" "$(camera_file "$file")" "$dir/corners.csv" || continue
      "$score" --truth "$sim/truth.yaml" --result "$dir/result31_pose_path.json" \
        --result "$dir/result31_corners.json" |
        sed "s|^$out/||"
    done
  done
done

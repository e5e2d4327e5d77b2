#!/usr/bin/env bash
# Issue "every pose counts", done-when: on simulated paper-protocol campaigns (Model 12
# and Model 31 robots, one per seed; the 71 calibration poses given without a `set`
# column, the 10 held-out poses' truth kept apart), the held-out error of the default
# commands (`identify --model 12`, then `--model 31 --from` it) against a fit on every
# pose (`--folds 0 --no-outlier-rejection`) and the former default (`--validation 10`).
# Error: board position predicted from the true joints vs the true board pose, RMS, mm
# (`h4cal fk --compare`). Usage: every_pose_counts.sh H4CAL OUT_DIR SEED...
h4cal=$1; out=$2; shift 2
mkdir -p "$out"
score() { "$h4cal" fk --result "$1" --joints "$2/heldout_joints.csv" --out "$2/fk.csv" --compare "$2/heldout_truth.csv" 2>/dev/null | sed -E 's/.*position RMS ([0-9.]+) mm.*/\1/'; }
for truth in 12 31; do
for seed in "$@"; do
  d=$out/m${truth}_s$seed
  "$h4cal" simulate --truth $truth --seed $seed --robot-seed $seed --out-dir "$d" 2>/dev/null
  # the 71 calibration poses, no set column: the held-out truth stays apart
  awk -F, 'NR==1{for(i=1;i<=NF;i++) if($i=="set") c=i} { if (NR>1 && $c=="valid") next; line=""; for(i=1;i<=NF;i++) if(i!=c) line=line (line==""?"":",") $i; print line }' "$d/dataset.csv" > "$d/data71.csv"
  "$h4cal" identify --robot "$d/robot.yaml" --data "$d/data71.csv" --model 12 --out "$d/r12.json" > "$d/r12.txt" 2>&1; rc12=$?
  "$h4cal" identify --robot "$d/robot.yaml" --data "$d/data71.csv" --model 12 --folds 0 --no-outlier-rejection --out "$d/r12_all.json" > /dev/null 2>&1
  "$h4cal" identify --robot "$d/robot.yaml" --data "$d/data71.csv" --model 12 --validation 10 --out "$d/r12_v10.json" > /dev/null 2>&1
  line="truth $truth seed $seed: M12 default $(score $d/r12.json $d) (exit $rc12, $(head -1 $d/r12.txt)) all-poses $(score $d/r12_all.json $d) old-default(--validation 10) $(score $d/r12_v10.json $d)"
  if [ $truth = 31 ]; then
    "$h4cal" identify --robot "$d/robot.yaml" --data "$d/data71.csv" --model 31 --from "$d/r12.json" --out "$d/r31.json" > "$d/r31.txt" 2>&1; rc31=$?
    "$h4cal" identify --robot "$d/robot.yaml" --data "$d/data71.csv" --model 31 --from "$d/r12_all.json" --folds 0 --no-outlier-rejection --out "$d/r31_all.json" > /dev/null 2>&1
    "$h4cal" identify --robot "$d/robot.yaml" --data "$d/data71.csv" --model 31 --from "$d/r12_v10.json" --out "$d/r31_v10.json" > /dev/null 2>&1
    line="$line | M31 --from default $(score $d/r31.json $d) (exit $rc31, $(head -1 $d/r31.txt)) all-poses $(score $d/r31_all.json $d) from-old-default $(score $d/r31_v10.json $d)"
  fi
  echo "$line"
done; done

#!/usr/bin/env bash
# Exit codes and versions as README.md documents them (issue 16): `--version` on both
# programs (exit 0, the CMake project version); `h4cam render` exits 3 and writes nothing
# when the board is behind the camera or off the image; `h4cam measure` exits 3 when no
# image shows the board (its rows are still written), 0 when one does; a dataset given as
# --robot (or a robot.yaml as --data) is named as such in one line (exit 1), in the one
# error style "h4cal: error: <file>:<line>: ..."; one dialect (docs/cli.md): new option names
# work, old spellings still work and --help shows only the new ones; the exported controller
# YAML does not call identified values "a priori".
#   cli_exit_codes_test.sh H4CAL H4CAM SOURCE_DIR VERSION WORK_DIR
set -euo pipefail
h4cal=$1 h4cam=$2 src=$3 version=$4 dir=$5
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir"
fail() { echo "FAIL: $*" >&2; exit 1; }
code() { local c=0; "$@" > out.txt 2>&1 || c=$?; echo $c; }

for program in "$h4cal" "$h4cam"; do
  name=$(basename "$program")
  [ "$(code "$program" --version)" -eq 0 ] || fail "$name --version: $(cat out.txt)"
  grep -qx "$name $version" out.txt || fail "$name --version printed '$(cat out.txt)'"
done

board=$src/boards/aprilgrid_6x6_30mm.yaml camera=$src/boards/sim_camera_1024x768.yaml
render() { code "$h4cam" render --board "$board" --camera "$camera" --pose "$1" --out-dir "$2"; }

c=$(render 0,0,-0.5,1,0,0,0 behind)
[ "$c" -eq 3 ] || fail "render behind the camera exited $c: $(cat out.txt)"
grep -q "behind the camera" out.txt || fail "render behind the camera said: $(cat out.txt)"
[ ! -e behind/frame_0000.png ] || fail "render behind the camera wrote a frame"
c=$(render 3,0,0.5,1,0,0,0 aside)
[ "$c" -eq 3 ] || fail "render off the image exited $c: $(cat out.txt)"
grep -q "off the image" out.txt || fail "render off the image said: $(cat out.txt)"

# In view but 30 m away (a few pixels wide): rendered, yet no image shows a usable board.
c=$(render -0.1,-0.1,30,1,0,0,0 far)
[ "$c" -eq 0 ] || fail "render of a far board exited $c: $(cat out.txt)"
c=$(code "$h4cam" measure --board "$board" --camera "$camera" --group 1 --out far.csv far)
[ "$c" -eq 3 ] || fail "measure with no board in sight exited $c: $(cat out.txt)"
grep -q "no image shows the board" out.txt || fail "measure said: $(cat out.txt)"
[ "$(wc -l < far.csv)" -eq 2 ] || fail "far.csv should hold the header and one row without a pose"

c=$(render -0.1,-0.1,0.5,1,0,0,0 near)
[ "$c" -eq 0 ] || fail "render of a near board exited $c: $(cat out.txt)"
c=$(code "$h4cam" measure --board "$board" --camera "$camera" --frames 1 --out near.csv near)
[ "$c" -eq 0 ] || fail "measure of a visible board exited $c: $(cat out.txt)"
# Old spellings: render --out (now --out-dir), measure --group (now --frames), same output.
c=$(code "$h4cam" render --board "$board" --camera "$camera" --pose -0.1,-0.1,0.5,1,0,0,0 \
  --out near_old)
[ "$c" -eq 0 ] || fail "render --out (old spelling) exited $c: $(cat out.txt)"
cmp -s near/frame_0000.png near_old/frame_0000.png || fail "render --out wrote another frame"
c=$(code "$h4cam" measure --board "$board" --camera "$camera" --group 1 --out near_old.csv near)
[ "$c" -eq 0 ] || fail "measure --group (old spelling) exited $c: $(cat out.txt)"
cmp -s near.csv near_old.csv || fail "measure --group and --frames differ"
# --help names the new spelling only.
help_shows() {  # program command new old
  "$1" "$2" --help > help.txt 2>&1 || fail "$2 --help failed"
  grep -q -- "$3" help.txt || fail "$2 --help does not show $3"
  ! grep -qE -- "$4([ ,=]|\$)" help.txt || fail "$2 --help shows the old spelling $4"
}
help_shows "$h4cam" render --out-dir --out
help_shows "$h4cam" measure --frames --group
help_shows "$h4cam" calibrate-intrinsics --distortion-model --model
help_shows "$h4cal" simulate --truth-model --truth
help_shows "$h4cal" identify --report-dir --report
help_shows "$h4cal" square-plan --square-mm --side-mm
help_shows "$h4cal" plan --count --poses
# robot.yaml and the dataset swapped: one line that says so, not the file quoted.
"$h4cal" simulate --truth 12 --out-dir sim 2> /dev/null || fail "simulate"
c=$(code "$h4cal" analyze --robot sim/dataset.csv --data sim/robot.yaml)
[ "$c" -eq 1 ] || fail "analyze with --robot and --data swapped exited $c: $(cat out.txt)"
grep -q "^h4cal: error: sim/dataset.csv:1: this looks like a dataset CSV, not a robot.yaml" out.txt \
  || fail "swapped --robot said: $(cut -c1-300 out.txt)"
[ "$(wc -l < out.txt)" -eq 1 ] || fail "swapped --robot printed $(wc -l < out.txt) lines"
! grep -q "^1,\|,1,[0-9]" out.txt || fail "swapped --robot quoted the dataset"
c=$(code "$h4cal" analyze --robot sim/robot.yaml --data sim/robot.yaml)
[ "$c" -eq 1 ] || fail "analyze with a robot.yaml as --data exited $c"
grep -q "^h4cal: error: sim/robot.yaml:1: this looks like a YAML file (a robot.yaml?), not a dataset CSV" out.txt \
  || fail "a robot.yaml as --data said: $(cut -c1-300 out.txt)"
# Other swapped files: one line naming what the file looks like, exit 1.
swapped() {  # program-and-args... ; the last line of the expected message is in $expect
  local c; c=$(code "$@")
  [ "$c" -eq 1 ] || fail "$* exited $c: $(cut -c1-300 out.txt)"
  grep -q "^$(basename "$1"): error: $expect" out.txt || fail "$* said: $(cut -c1-300 out.txt)"
  [ "$(wc -l < out.txt)" -eq 1 ] || fail "$* printed $(wc -l < out.txt) lines"
}
expect="sim/dataset.csv:1: this looks like a dataset CSV, not a JSON file"
swapped "$h4cal" fk --result sim/dataset.csv --joints sim/heldout_joints.csv --out fk.csv
expect="sim/robot.yaml:1: this looks like a YAML file, not a JSON file"
swapped "$h4cal" export --result sim/robot.yaml --out x.yaml
expect="sim/robot.yaml:1: this looks like a YAML file, not a CSV file"
swapped "$h4cal" ik --robot sim/robot.yaml --poses sim/robot.yaml --out j.csv
expect="sim/dataset.csv:1: this looks like a dataset CSV, not a YAML file"
swapped "$h4cam" measure --board "$board" --camera sim/dataset.csv --out m.csv near
swapped "$h4cam" measure --board sim/dataset.csv --camera "$camera" --out m.csv near
expect="$camera:1: this looks like a camera file, not a board YAML (were --board and --camera swapped?)"
swapped "$h4cam" measure --board "$camera" --camera "$board" --out m.csv near
expect="$board:1: this looks like a board file, not a camera YAML (were --board and --camera swapped?)"
swapped "$h4cam" capture --source sim --board "$board" --camera "$board" --count 1 --out frames
# Errors name the options by their names, not their old spellings.
c=$(code "$h4cam" preview --source sim --board "$board" --camera "$camera" --count 1 --draw)
[ "$c" -eq 1 ] && grep -q -- "--draw needs --out-dir" out.txt || fail "preview --draw: $(cat out.txt)"
c=$(code "$h4cal" square-plan --square-mm 0 --out sq.csv)
[ "$c" -eq 1 ] && grep -q -- "(--square-mm > 0" out.txt || fail "square-plan --square-mm 0: $(cat out.txt)"
# The old spelling simulate --truth and the new --truth-model draw the same robot.
"$h4cal" simulate --truth-model 12 --out-dir sim_new 2> /dev/null || fail "simulate --truth-model"
cmp -s sim/truth.yaml sim_new/truth.yaml || fail "simulate --truth and --truth-model differ"
# An identified robot exported for the controller is not labelled a priori.
c=$(code "$h4cal" identify --robot sim/robot.yaml --data sim/dataset.csv --model 12 --folds 0 \
  --out result12.json)
[ "$c" -le 3 ] && [ -s result12.json ] || fail "identify exited $c: $(tail -3 out.txt)"
expect="result12.json:1: this looks like a JSON file, not a CSV file"
swapped "$h4cal" identify --robot sim/robot.yaml --data result12.json --out r.json
"$h4cal" export --result result12.json --out controller.yaml 2> /dev/null || fail "export"
grep -q "identified camera pose in base" controller.yaml || fail "export: $(head -3 controller.yaml)"
! grep -q "a priori" controller.yaml || fail "export labels values a priori: $(grep 'a priori' controller.yaml)"
# A result whose verdict is not good is exported with its verdict repeated and exit 3.
sed 's/"code": "[a-z_]*"/"code": "model_cannot_describe"/' result12.json > bad12.json
grep -q '"code": "model_cannot_describe"' bad12.json || fail "no verdict code to change in result12.json"
c=$(code "$h4cal" export --result bad12.json --out bad_controller.yaml)
[ "$c" -eq 3 ] && [ -s bad_controller.yaml ] || fail "export of a not-good result exited $c"
grep -q "its verdict is model_cannot_describe, not good" out.txt || fail "export did not warn: $(cat out.txt)"
echo "PASS: --version on both; render 3 behind / off the image; measure 3 with no board, 0 with" \
  "one; swapped --robot / --data named as such; new and old option spellings; export labels"

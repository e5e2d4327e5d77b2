#!/usr/bin/env bash
# The calibration report end to end: the paper scenario simulated, identified (Models 12
# and 31), reported; the page opened in headless Chromium must hold every section and
# figure, log no console error, render a non-blank screenshot, and lay out without clipping
# or overlap at desktop (1920) and laptop (1366) widths (report_layout_check.js). Bad input (a result of
# the other model, a dataset missing held-out poses, an unreachable square) must fail with
# a clear message and write no report. Exit 77 (skipped) when Chromium is missing.
set -uo pipefail
. "$(dirname "$0")/h4cal_test_lib.sh"

sim=$dir/sim
"$h4cal" simulate --paper --out-dir "$sim" 2>/dev/null || fail "simulate --paper"
for f in straightness_1.csv straightness_2.csv; do
  [ -s "$sim/$f" ] || fail "simulate wrote no $f"
done
"$h4cal" identify --robot "$sim/robot.yaml" --data "$sim/dataset.csv" --model 12 \
  --out "$sim/result12.json" > /dev/null 2>&1 || fail "identify 12"
"$h4cal" identify --robot "$sim/robot.yaml" --data "$sim/dataset.csv" --model 31 \
  --from "$sim/result12.json" --out "$sim/result31.json" > /dev/null 2>&1 || fail "identify 31"
"$h4cal" report --sim-dir "$sim" --report-dir "$dir/report" 2> "$dir/report.log" ||
  fail "report: $(cat "$dir/report.log")"
html=$dir/report/report.html
[ -s "$html" ] || fail "no report.html"
sections="verdict summary parameters identifiability table2 table3 positioning accuracy-map
          camera residuals histograms table4 straightness square square-plot four-dof notes"
for id in $sections; do
  grep -q "<section id=\"$id\">" "$html" || fail "report.html has no section $id"
  # The table of contents links every section after the verdict.
  [ "$id" = verdict ] || grep -q "<li><a href=\"#$id\">" "$html" || fail "contents lack $id"
done
# The verdict comes first, then the contents, then the details.
verdict_line=$(grep -n '<section id="verdict">' "$html" | cut -d: -f1)
contents_line=$(grep -n '<nav id="contents">' "$html" | cut -d: -f1)
summary_line=$(grep -n '<section id="summary">' "$html" | cut -d: -f1)
[ -n "$contents_line" ] && [ "$verdict_line" -lt "$contents_line" ] &&
  [ "$contents_line" -lt "$summary_line" ] || fail "report order: verdict, contents, details"
grep -q "a priori positioning error, every pose (RMS, mm / deg)" "$html" ||
  fail "the summary's angles are not in deg"
grep -q "<tr><th>alpha1</th><td>deg</td>" "$html" && grep -q "<tr><th>h</th><td>mm</td>" "$html" ||
  fail "the parameter table is not in mm and deg"
[ "$(grep -c "residual (deg)" "$html")" -ge 2 ] || fail "the residual plots are not in deg"
# Residuals, histograms, straightness, square, and an accuracy map per model (12 and 31).
[ "$(grep -o '<svg' "$html" | wc -l)" -eq 6 ] || fail "report.html does not hold 6 figures"
[ "$(sed -n '/<section id="accuracy-map">/,/<\/section>/p' "$html" | grep -c '<svg')" -eq 2 ] ||
  fail "the accuracy map is not drawn for both models"
# The accuracy map: CSV per identified model beside the page, a row per reachable map pose
# (13 x 13 X-Y positions, 3 levels, 3 rotations at most), the figure of Model 31.
for m in 12 31; do
  csv=$dir/report/accuracy_map_model$m.csv
  [ "$(head -1 "$csv")" = "X,Y,Z,theta,position_sigma,theta_sigma" ] ||
    fail "accuracy_map_model$m.csv: no header"
  rows=$(($(wc -l < "$csv") - 1))
  [ "$rows" -gt 1000 ] && [ "$rows" -le 1521 ] || fail "accuracy_map_model$m.csv: $rows rows"
done
grep -q "<th>Model 31: Z from the centre (mm)</th>" "$html" || fail "no Model 31 accuracy map table"
grep -q "before calibration (paper)" "$html" || fail "no paper rows on the paper scenario"
# Every section is computed but the camera's: the paper's campaign has no corners and its
# results come from the pose path (the camera section says so once; the corner path test
# fills it).
[ "$(grep -c "Not computed" "$html")" -eq 1 ] || fail "a section was not computed"
sed -n '/<section id="camera">/,/<\/section>/p' "$html" | grep -q "Not computed: the results come from the pose path" ||
  fail "the camera section does not say why it is empty"

# validate prints the tables and --report writes the same page.
"$h4cal" validate --sim-dir "$sim" --report "$dir/validate" > "$dir/validate.txt" 2>&1 ||
  fail "validate: $(cat "$dir/validate.txt")"
grep -q "Table 3" "$dir/validate.txt" || fail "validate printed no Table 3"
grep -q "Accuracy map, Model 31: predicted 1-sigma position error median" "$dir/validate.txt" ||
  fail "validate printed no accuracy map line"
[ -s "$dir/validate/report.html" ] || fail "validate --report wrote no report.html"

# A real held-out set is labelled as one, in RMS.
grep -q "Model 31 positioning error, held out (10 poses not in the fit) (RMS, mm / deg)" "$html" ||
  fail "the summary does not say the 10 held-out poses were not in the fit"

# Every pose in the fit (identify's default): identify, validate and the report call the
# figures on the dataset's poses in-sample, never held out, beside the cross-validated RMS.
all=$dir/all
"$h4cal" simulate --truth 12 --validation 0 --out-dir "$all" > /dev/null 2>&1 ||
  fail "simulate --validation 0"
"$h4cal" identify --robot "$all/robot.yaml" --data "$all/dataset.csv" --model 12 \
  --out "$all/result12.json" > "$all/identify.txt" 2>&1 || fail "identify, every pose in the fit"
grep -q "board pose error, 10-fold cross-validated (held-out) RMS over 81 poses" \
  "$all/identify.txt" || fail "identify: no cross-validated RMS: $(cat "$all/identify.txt")"
"$h4cal" validate --sim-dir "$all" --report "$all/report" > "$all/validate.txt" 2>&1 ||
  fail "validate, every pose in the fit: $(cat "$all/validate.txt")"
grep -q "Table 3: joint residuals, in-sample (81 poses, none held out of the fit)" "$all/validate.txt" ||
  fail "validate: Table 3 not labelled in-sample: $(cat "$all/validate.txt")"
grep -q "Model 12   10-fold cross-validated (held-out) RMS over 81 poses: " "$all/validate.txt" ||
  fail "validate: no cross-validated RMS"
! grep -Eq "held out:|held-out poses|\(mean\)" "$all/validate.txt" ||
  fail "validate calls in-sample figures held out, or a mean an accuracy"
! grep -Eiq "held out for validation|held-out pose" "$all/report/report.html" ||
  fail "the report calls in-sample poses held out"
grep -q "<th>Model 12 board pose error, 10-fold cross-validated (held-out) RMS over 81 poses" \
  "$all/report/report.html" || fail "the report's summary has no cross-validated headline"

# Controller export: Model 12 in robot.yaml keys; Model 31 its own block.
"$h4cal" export --result "$sim/result12.json" --out "$dir/controller12.yaml" 2>/dev/null ||
  fail "export 12"
grep -q "^model12:" "$dir/controller12.yaml" || fail "export 12 has no model12 block"
"$h4cal" export --result "$sim/result31.json" --robot "$sim/robot.yaml" \
  --out "$dir/controller31.yaml" 2>/dev/null || fail "export 31"
grep -q "^model31:" "$dir/controller31.yaml" || fail "export 31 has no model31 block"
out=$("$h4cal" export --result "$sim/result31.json" --out "$dir/c.yaml" 2>&1)
[ $? -ne 0 ] || fail "export 31 without --robot accepted"

# Bad input: clear message, no report.
expect_error() {  # name, expected message, args...
  local name=$1 message=$2; shift 2
  local out
  out=$("$h4cal" report "$@" --report-dir "$dir/bad_$name" 2>&1)
  [ $? -ne 0 ] || fail "$name: accepted"
  echo "$out" | grep -q "$message" || fail "$name: unclear message: $out"
  [ ! -e "$dir/bad_$name/report.html" ] || fail "$name: a report was written"
}
expect_error other_model "Model 31 result given to --result12" --sim-dir "$sim" \
  --result12 "$sim/result31.json"
valid_id=$(grep ',valid' "$sim/dataset.csv" | head -1 | cut -d, -f1)
grep -v "^$valid_id," "$sim/dataset.csv" > "$dir/missing.csv"
expect_error missing_pose "pose $valid_id is missing" --sim-dir "$sim" --data "$dir/missing.csv"
expect_error square "out of the controller's reach" --sim-dir "$sim" --square-mm 2000

# Headless Chromium: DOM, console, screenshot.
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "SKIP: chromium is not installed (scripts/setup --report installs it); the report" \
       "itself was checked" >&2
  exit 77
fi
base_flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
            --disable-background-networking --disable-component-update --disable-sync
            --enable-logging=stderr --v=0)
flags=("${base_flags[@]}" --window-size=1280,6000)
profile=$(mktemp -d)
timeout 120 "$browser" "${flags[@]}" --user-data-dir="$profile" --dump-dom "file://$html" \
  > "$dir/dom.html" 2> "$dir/chromium_dom.log" || fail "chromium --dump-dom failed"
rm -rf "$profile"
for id in $sections; do
  grep -q "<section id=\"$id\">" "$dir/dom.html" || fail "the rendered DOM has no section $id"
done
[ "$(grep -o '<svg' "$dir/dom.html" | wc -l)" -eq 6 ] || fail "the rendered DOM lacks figures"
profile=$(mktemp -d)
timeout 120 "$browser" "${flags[@]}" --user-data-dir="$profile" \
  --screenshot="$dir/report.png" "file://$html" 2> "$dir/chromium_shot.log" ||
  fail "chromium --screenshot failed"
rm -rf "$profile"
if grep -h "CONSOLE" "$dir/chromium_dom.log" "$dir/chromium_shot.log"; then
  fail "console messages while rendering the report"
fi
[ -s "$dir/report.png" ] || fail "no screenshot"
# A blank page compresses to a few kB; tables and four plots do not.
size=$(stat -c %s "$dir/report.png")
[ "$size" -gt 100000 ] || fail "screenshot of $size bytes looks blank"

# Layout at desktop and laptop widths: a scratch copy of the page with the layout check
# injected (the report itself has no script) reports clipping, overlap and empty figures
# into its DOM; then a screenshot of the whole page height at that width.
layout_check=$(dirname "$0")/report_layout_check.js
with_check() {  # page, copy: the copy with the layout check run on load
  { sed '/<\/body>/,$d' "$1"; echo "<script>"; cat "$layout_check"; echo "</script>";
    echo "</body></html>"; } > "$2"
}
check_layout() {  # page, width: the rendered DOM, with the check's findings, in $dir/layout.html
  local profile
  profile=$(mktemp -d)
  timeout 120 "$browser" "${base_flags[@]}" --window-size="$2,1080" --user-data-dir="$profile" \
    --virtual-time-budget=5000 --dump-dom "file://$1" > "$dir/layout.html" 2> /dev/null
  rm -rf "$profile"
}
layout_findings() {  # the findings of the last check_layout, "layout ok" when none
  sed -n '/<pre id="layout-check" data-height/,/<\/pre>/p' "$dir/layout.html" | sed 's/<[^>]*>//g'
}
page_height() {  # the page's height in px, as the last check_layout measured it
  grep -o 'id="layout-check" data-height="[0-9]*"' "$dir/layout.html" | grep -o '[0-9]*"$' |
    tr -d '"'
}
# The check must see a broken layout: an element wider than the window, two blocks on
# top of each other.
sed 's|<h1>H4 calibration report</h1>|&<div style="width:3000px;height:4px"></div><p style="margin-bottom:-40px">a</p><p>b</p>|' \
  "$html" > "$dir/broken.html"
with_check "$dir/broken.html" "$dir/broken_check.html"
check_layout "$dir/broken_check.html" 1366
findings=$(layout_findings)
echo "$findings" | grep -q "px wide in a 1366 px window" &&
  echo "$findings" | grep -q "p and p overlap" ||
  fail "the layout check misses a too-wide element or an overlap: $findings"
with_check "$html" "$dir/checked.html"
for width in 1920 1366; do
  check_layout "$dir/checked.html" "$width"
  findings=$(layout_findings)
  [ "$findings" = "layout ok" ] || fail "layout at $width px wide: $findings"
  height=$(page_height)
  [ -n "$height" ] && [ "$height" -gt 1080 ] || fail "no page height at $width px: '$height'"
  profile=$(mktemp -d)
  timeout 120 "$browser" "${base_flags[@]}" --window-size="$width,$height" \
    --user-data-dir="$profile" --screenshot="$dir/report_$width.png" "file://$html" \
    2> "$dir/chromium_shot_$width.log" ||
    fail "chromium --screenshot at $width px failed"
  rm -rf "$profile"
  [ "$(stat -c %s "$dir/report_$width.png")" -gt 100000 ] ||
    fail "the screenshot at $width px looks blank"
done
echo "PASS"

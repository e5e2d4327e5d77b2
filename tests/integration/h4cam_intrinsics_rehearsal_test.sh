#!/usr/bin/env bash
# The README's intrinsics rehearsal on the simulated camera, command for command (issue 26
# point 5): sim captures at a sequence of poses, a second capture numbered on (never
# overwriting), calibrate-intrinsics succeeding, and its report files well-formed: the SVGs
# parse as XML, the HTML page links them and the camera file.
# Usage: h4cam_intrinsics_rehearsal_test.sh H4CAM SOURCE_DIR SCRATCH_DIR
set -uo pipefail
h4cam=$1 src=$2 dir=$3
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || exit 1
board=$src/boards/checkerboard_9x6_25mm.yaml camera=$src/boards/sim_camera_1024x768.yaml

"$h4cam" capture --source sim --board "$board" --camera "$camera" --count 11 \
  --out-dir intrinsics > capture1.txt || fail "capture: $(cat capture1.txt)"
"$h4cam" capture --source sim --board "$board" --camera "$camera" --count 1 \
  --out-dir intrinsics > capture2.txt || fail "second capture: $(cat capture2.txt)"
grep -q "^frame 11: board ok, chessboard: 54/54 corners" capture2.txt ||
  fail "the second capture is not frame 11 with the whole chessboard: $(cat capture2.txt)"
! grep -q "0/0 tags" capture1.txt capture2.txt || fail "a chessboard line reads 0/0 tags"
[ "$(ls intrinsics/frame_*.png | wc -l)" = 12 ] || fail "expected 12 frames: $(ls intrinsics)"

"$h4cam" calibrate-intrinsics --board "$board" intrinsics/frame_*.png --out camera.yaml \
  > calibrate.txt || fail "calibrate-intrinsics: $(cat calibrate.txt)"
grep -q "12 of 12 views used" calibrate.txt || fail "not every view used: $(cat calibrate.txt)"
for f in camera.yaml camera-report.html camera-coverage.svg camera-residuals.svg \
  camera-report.txt; do
  [ -s "$f" ] || fail "$f missing"
done

python3 - <<'PY' || fail "the report files are not well-formed"
import html.parser, sys, xml.etree.ElementTree as ET
for svg in ("camera-coverage.svg", "camera-residuals.svg"):
    root = ET.parse(svg).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg", (svg, root.tag)
class Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.links = set()
    def handle_starttag(self, tag, attrs):
        self.links.update(v for k, v in attrs if k in ("href", "src"))
page = Links()
page.feed(open("camera-report.html").read())
missing = {"camera.yaml", "camera-coverage.svg", "camera-residuals.svg"} - page.links
assert not missing, missing
print("report files well-formed, links", sorted(page.links))
PY
echo "PASS: rehearsal captured 12 frames and calibrated; report files well-formed"

#!/usr/bin/env bash
# The realistic camera file of h4_camera_study (common/README.md#the-camera-files-uncertainty): 25
# views of the 9 x 6 chessboard rendered through the true camera (boards/sim_camera_1024x768.yaml)
# with a camera module's image formation (h4cam render --preset processed: defocus, illumination
# gradient, shot noise, sRGB response), then calibrated by `h4cam calibrate-intrinsics` as a user
# calibrates. Its error against the true camera comes from the views and the detector, not from a
# drawn number; its intrinsics_covariance is what the calibration claims.
#   host/bench/calibrated_camera_file.sh H4CAM OUT.yaml [WORK_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
[ $# -ge 2 ] || { sed -n '2,9p' "$0" >&2; exit 2; }
h4cam=$1 out=$2 work=${3:-$(mktemp -d)}
camera=$root/boards/sim_camera_1024x768.yaml
board=$root/boards/checkerboard_9x6_25mm.yaml
mkdir -p "$work/views"

# View i: the board's centre at image point (u, v) of a 3 x 3 grid, at one of three depths,
# turned about x, y and z by up to 35, 35 and 15 deg; X_CT as x y z qw qx qy qz. The board
# frame's origin is its first inner corner, the board spans 200 x 125 mm from it.
poses() {
  awk 'BEGIN {
    fx = 817; fy = 816.2; cx = 515.3; cy = 380.7; d2r = atan2(0, -1) / 180
    for (i = 0; i < 25; ++i) {
      u = 1024 * (0.3 + 0.2 * (i % 3)); v = 768 * (0.3 + 0.2 * (int(i / 3) % 3))
      z = 0.45 + 0.12 * (int(i / 9) % 3)
      rx = 35 * sin(2.4 * i) * d2r; ry = 35 * cos(1.7 * i) * d2r; rz = 15 * sin(i) * d2r
      # q = qz * qy * qx
      ax = rx / 2; ay = ry / 2; az = rz / 2
      qw = cos(az) * cos(ay) * cos(ax) + sin(az) * sin(ay) * sin(ax)
      qx = cos(az) * cos(ay) * sin(ax) - sin(az) * sin(ay) * cos(ax)
      qy = cos(az) * sin(ay) * cos(ax) + sin(az) * cos(ay) * sin(ax)
      qz = sin(az) * cos(ay) * cos(ax) - cos(az) * sin(ay) * sin(ax)
      # R (from q) times the board centre (0.1, 0.0625, 0), taken off the target point
      bx = 0.1; by = 0.0625
      r00 = 1 - 2 * (qy * qy + qz * qz); r01 = 2 * (qx * qy - qz * qw)
      r10 = 2 * (qx * qy + qz * qw); r11 = 1 - 2 * (qx * qx + qz * qz)
      r20 = 2 * (qx * qz - qy * qw); r21 = 2 * (qy * qz + qx * qw)
      tx = (u - cx) / fx * z - (r00 * bx + r01 * by)
      ty = (v - cy) / fy * z - (r10 * bx + r11 * by)
      tz = z - (r20 * bx + r21 * by)
      printf "%.6f %.6f %.6f %.12f %.12f %.12f %.12f\n", tx, ty, tz, qw, qx, qy, qz
    }
  }'
}

i=0
images=()
while read -r -a pose; do
  dir=$work/views/$(printf %02d $i)
  if "$h4cam" render --board "$board" --camera "$camera" --pose "${pose[@]}" --preset processed \
      --seed $((i + 1)) --out-dir "$dir" > /dev/null 2>&1; then
    images+=("$dir/frame_0000.png")
  else
    echo "view $i: the board is not in view, left out" >&2
  fi
  i=$((i + 1))
done < <(poses)
"$h4cam" calibrate-intrinsics --board "$board" --out "$out" "${images[@]}"

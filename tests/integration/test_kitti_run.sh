#!/usr/bin/env bash
# The pipeline on real KITTI frames (../shared/data/kitti_raw_0926_seq; skipped
# when absent): all 11 frames come out, the camera height from EXTRINSICS is
# within 0.3 m of 1.65 m on every frame, and a kept detection covers the car
# ahead in frame 0 (label box 605,176 - 681,234) with IoU > 0.5.
source "$(dirname "$0")/lib.sh"
data="${NERV_SHARED_DATA:-$NERV_ROOT/../shared/data}/kitti_raw_0926_seq"
[[ -d "$data" ]] || { echo "SKIP: $data is absent"; exit 77; }
enter_private_bus "$@"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

"$NERV_ROOT/tools/nerv" run --data "$data" --out "$out" --rate 5 --timeout 30 || fail "nerv run exited with $?"
no_survivors || fail "processes survived"
grep -q '"frames_out":11' "$out/summary.json" || fail "not all 11 frames detected: $(head -c 200 "$out/summary.json")"
pass "11 frames in, 11 out"

heights=$(grep -o '"height_m":[-0-9.e+]*' "$out/summary.json" | cut -d: -f2)
[[ $(echo "$heights" | wc -l) -eq 11 ]] || fail "expected 11 heights, got: $heights"
echo "$heights" | awk '{ d = $1 - 1.65; if (d < 0) d = -d; if (d > 0.3) bad = bad " " $1 } END { if (bad != "") { print "heights off by > 0.3 m:" bad; exit 1 } }' \
  || fail "camera height"
pass "camera height within 0.3 m of 1.65 m on every frame: $(echo $heights)"

"$BIN/nerv_export" "$out/nerv.lcmlog" --json --no-blobs | grep '"channel":"DETECTIONS"' \
  | grep '"header":{"seq":0,' >"$out/det0.json" || fail "no DETECTIONS for frame 0"
best=$(best_kept_iou "$out/det0.json" 605 176 681 234)
awk -v b="$best" 'BEGIN { exit !(b > 0.5) }' || fail "best IoU of a kept detection with the car ahead is $best"
pass "car ahead detected, IoU $best"
echo "1 passed, 0 failed"

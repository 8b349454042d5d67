#!/usr/bin/env bash
# Raw (distorted, unaligned) frames through the real services: the KITTI frames of
# ../shared/data/kitti_raw_0926_seq (skipped when absent) turned into the raw views of
# a rig with lens distortion and turned cameras (nerv_unrectify), played with their
# raw_calib.yaml. The stereo_matcher rectifies them on ingest. Checked over LCM:
# STEREO_FRAME goes out raw, DISPARITY comes back rectified with the pinhole that
# rectification gives, all 11 frames come out, the camera pose agrees with the run on
# the rectified frames (height within 0.03 m, pitch within 0.2 deg on every frame), and
# the car ahead in frame 0 is detected at its moved label box.
source "$(dirname "$0")/lib.sh"
data="${NERV_SHARED_DATA:-$NERV_ROOT/../shared/data}/kitti_raw_0926_seq"
[[ -d "$data" ]] || { echo "SKIP: $data is absent"; exit 77; }
enter_private_bus "$@"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$BIN/nerv_unrectify" --data "$data" --out "$work/raw" >"$work/unrectify.txt" || fail "nerv_unrectify: $(cat "$work/unrectify.txt")"
fx=$(sed -n 's/^rectified camera: fx \([0-9.]*\) .*/\1/p' "$work/unrectify.txt")
[[ -n "$fx" ]] || fail "nerv_unrectify printed no rectified camera: $(cat "$work/unrectify.txt")"
[[ -f "$work/raw/raw_calib.yaml" && ! -f "$work/raw/calib.yaml" ]] || fail "the raw folder needs raw_calib.yaml and no calib.yaml"

for run in raw rect; do
  src="$work/raw"; [[ $run == rect ]] && src="$data"
  "$NERV_ROOT/tools/nerv" run --data "$src" --out "$work/$run" --rate 5 --timeout 30 >"$work/$run.txt" 2>&1 \
    || fail "nerv run on the $run frames exited with $?: $(tail -5 "$work/$run.txt")"
  no_survivors || fail "processes survived"
  grep -q '"frames_out":11' "$work/$run/summary.json" || fail "$run: not all 11 frames detected: $(head -c 200 "$work/$run/summary.json")"
done
pass "11 raw frames in, 11 out"

"$BIN/nerv_export" "$work/raw/nerv.lcmlog" --json --no-blobs >"$work/raw.jsonl" || fail "nerv_export"
frame_calib=$(grep -m1 '"channel":"STEREO_FRAME"' "$work/raw.jsonl" | grep -o '"calib":{[^}]*}')
disp_calib=$(grep -m1 '"channel":"DISPARITY"' "$work/raw.jsonl" | grep -o '"calib":{[^}]*}')
[[ "$frame_calib" == *'"rectified":false'* ]] || fail "STEREO_FRAME was not sent raw: $frame_calib"
[[ "$disp_calib" == *'"rectified":true'* ]] || fail "DISPARITY is not marked rectified: $disp_calib"
got_fx=$(echo "$disp_calib" | grep -o '"fx":[0-9.e+-]*' | cut -d: -f2)
awk -v a="$got_fx" -v b="$fx" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d < 1e-4) }' \
  || fail "DISPARITY fx $got_fx, rectification gives $fx"
pass "STEREO_FRAME raw, DISPARITY rectified with fx $got_fx (the original 721.5377)"

values() { grep -o "\"$1\":[-0-9.e+]*" "$work/$2/summary.json" | cut -d: -f2; }
for key in height_m pitch_deg; do
  limit=0.03; [[ $key == pitch_deg ]] && limit=0.2
  paste <(values $key raw) <(values $key rect) | awk -v k="$key" -v lim="$limit" '
    { n++; d = $1 - $2; if (d < 0) d = -d; if (d > worst) worst = d; if (d > lim) bad = bad " " NR - 1 }
    END { printf "%s: %d frames, largest difference %.4f\n", k, n, worst
          if (n != 11 || bad != "") { print k " differs by more than " lim " on frames" bad; exit 1 } }' \
    || fail "pose from raw frames"
done
pass "camera height and pitch from the raw frames agree with the rectified run"

# The car ahead in frame 0: label 605,176-681,234 moved by nerv_unrectify.
x1= y1= x2= y2=
read -r x1 y1 x2 y2 < <(awk '$1 == "Car" && $14 > 19 && $14 < 20 { print $5, $6, $7, $8; exit }' "$work/raw/label_2/0000000000.txt") || true
[[ -n "${x2:-}" ]] || fail "no moved label for the car ahead"
grep '"channel":"DETECTIONS"' "$work/raw.jsonl" | grep '"header":{"seq":0,' >"$work/det0.json" || fail "no DETECTIONS for frame 0"
best=$(best_kept_iou "$work/det0.json" "$x1" "$y1" "$x2" "$y2")
awk -v b="$best" 'BEGIN { exit !(b > 0.5) }' || fail "best IoU of a kept detection with the car ahead is $best"
pass "car ahead detected in the raw frames, IoU $best"
echo "3 passed, 0 failed"

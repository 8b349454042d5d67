#!/usr/bin/env bash
# The stixel stage down: there are no hypotheses, so no DETECTIONS, but the camera pose goes
# on. Once two frames in a row went without STIXELS, snv_extrinsic publishes EXTRINSICS for
# every frame at once from the disparity alone (and no SURFACE_NORMALS, which only serve
# hypotheses); when the stixel stage is back, DETECTIONS come again, every one validated.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT
stage_down_and_back stixel "--no-wait" "$tmp"
resumed_us=$STAGE_BACK_US

"$BIN/nerv_export" "$tmp/run.lcmlog" --json --no-blobs >"$tmp/all.jsonl"
# EXTRINSICS while the stixel stage was down: received [us], capture [us], valid, height [m].
grep '"channel":"EXTRINSICS"' "$tmp/all.jsonl" | awk -v r="$resumed_us" '
  { ev = $0; sub(/.*"channel":"EXTRINSICS","utime":/, "", ev); sub(/[^0-9].*/, "", ev)
    h = $0; sub(/.*"header":\{"seq":[0-9]+,"utime":/, "", h); sub(/[^0-9].*/, "", h)
    v = ($0 ~ /"valid":true/); m = $0; sub(/.*"height_m":/, "", m); sub(/[^0-9.].*/, "", m)
    if (ev < r) print ev, h, v, m }' >"$tmp/down.txt"
n=$(wc -l <"$tmp/down.txt")
((n == 40)) || fail "$n EXTRINSICS for the 40 frames while the stixel stage was down"
read -r late worst bad hmin hmax <<<"$(awk 'NR == 1 { t0 = $2; lo = 99 } $2 - t0 >= 3000000 { n++; l = ($1 - $2) / 1000; if (l > w) w = l;
    if (!$3) b++; if ($4 < lo) lo = $4; if ($4 > hi) hi = $4 } END { printf "%d %.0f %d %.3f %.3f", n, w, b, lo, hi }' "$tmp/down.txt")"
((late >= 5)) || fail "only $late EXTRINSICS from 3 s on"
((worst < 1000)) || fail "EXTRINSICS came up to $worst ms after capture with the stixel stage down"
((bad == 0)) || fail "$bad of the poses from 3 s on were not valid"
awk -v lo="$hmin" -v hi="$hmax" 'BEGIN { exit !(lo > 1.60 && hi < 1.70) }' || fail "camera height $hmin..$hmax m, the scene's is 1.65 m"
down_normals=$(grep '"channel":"SURFACE_NORMALS"' "$tmp/all.jsonl" | awk -v r="$resumed_us" '
  { ev = $0; sub(/.*"utime":/, "", ev); sub(/[^0-9].*/, "", ev); if (ev < r) n++ } END { print n + 0 }')
((down_normals == 0)) || fail "$down_normals SURFACE_NORMALS without STIXELS"
pass "stixel stage down: $n of 40 frames with EXTRINSICS, from 3 s on $late within $worst ms, all valid, height $hmin..$hmax m (truth 1.65), no SURFACE_NORMALS"

dets=$(grep '"channel":"DETECTIONS"' "$tmp/all.jsonl" | wc -l)
[[ "$dets" -eq 10 ]] || fail "$dets DETECTIONS after the stixel stage came back, expected 10"
if grep -q "join_timeout: frame [0-9]*: no DISPARITY" "$tmp/up.log"; then
  fail "STIXELS taken for frames without DISPARITY: $(grep 'no DISPARITY' "$tmp/up.log" | head -3)"
fi
# The stixel stage announces itself in NERV_HEALTH before its first STIXELS, and from then on
# snv_extrinsic waits for them: every frame's normals come, so every frame is validated.
# (A frame validated without normals has no hypothesis labelled object, ground or error.)
alone=$(grep '"channel":"DETECTIONS"' "$tmp/all.jsonl" | { grep -vcE '"label":"(object|ground|error)"' || true; })
((alone == 0)) || fail "$alone DETECTIONS after the stixel stage came back without normals (all unvalidated)"
back_normals=$(grep -c '"channel":"SURFACE_NORMALS"' "$tmp/all.jsonl")
((back_normals == 10)) || fail "$back_normals SURFACE_NORMALS after the stixel stage came back, expected 10"
pass "stixel stage back: 10 of 10 frames detected, each with its normals and validated"
no_survivors || fail "processes survived"
echo "2 passed, 0 failed"

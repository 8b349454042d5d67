#!/usr/bin/env bash
# snv_extrinsic down: the validator publishes every frame's hypotheses as "unvalidated", and
# once two frames in a row went without normals it does so at once instead of waiting for each
# frame's (join_timeout_ms, 2 s, or until join_capacity newer frames wait: 0.8 s at 10 Hz).
# When snv_extrinsic is back, every frame is validated again, the first included (it announced
# itself in NERV_HEALTH before its first normals), also when the source restarted its count.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT
stage_down_and_back snv_extrinsic "--drain-timeout 20" "$tmp"
resumed_us=$STAGE_BACK_US

# One line per DETECTIONS: received [us], seq, capture [us], unvalidated, validated.
"$BIN/nerv_export" "$tmp/run.lcmlog" --json --no-blobs | grep '"channel":"DETECTIONS"' | awk '
  { ev = $0; sub(/.*"channel":"DETECTIONS","utime":/, "", ev); sub(/[^0-9].*/, "", ev)
    h = $0; sub(/.*"header":\{"seq":/, "", h); split(h, f, /[^0-9]+/)
    un = gsub(/"label":"unvalidated"/, "&"); va = gsub(/"label":"(object|ground|error)"/, "&")
    print ev, f[1], f[2], un, va }' >"$tmp/det.txt"
awk -v r="$resumed_us" '$1 < r' "$tmp/det.txt" >"$tmp/down.txt"
awk -v r="$resumed_us" '$1 >= r' "$tmp/det.txt" >"$tmp/back.txt"
[[ $(wc -l <"$tmp/down.txt") -eq 40 ]] || fail "$(wc -l <"$tmp/down.txt") DETECTIONS while snv_extrinsic was down, expected 40"
awk '$5 > 0 { bad = 1 } END { exit bad }' "$tmp/down.txt" || fail "a hypothesis was validated without normals"
# Frames captured 3 s after the first (at most 2 s of waiting, then the switch) come out at once.
read -r n worst <<<"$(awk 'NR == 1 { t0 = $3 } $3 - t0 >= 3000000 { n++; l = ($1 - $3) / 1000; if (l > w) w = l }
                          END { printf "%d %.0f", n, w }' "$tmp/down.txt")"
((n >= 5)) || fail "only $n frames after the switch"
((worst < 1000)) || fail "with snv_extrinsic down, frames still came out up to $worst ms after capture"
first=$(awk 'NR == 1 { printf "%.0f", ($1 - $3) / 1000 }' "$tmp/down.txt")
pass "snv_extrinsic down: 40 of 40 frames out, all unvalidated; the first after $first ms (waiting for its normals), the $n from 3 s on within $worst ms"

[[ $(wc -l <"$tmp/back.txt") -eq 10 ]] || fail "$(wc -l <"$tmp/back.txt") DETECTIONS after snv_extrinsic came back, expected 10"
# Alone until normals come, then validated: never alone again after a validated frame.
awk '$5 > 0 { seen = 1 } seen && $5 == 0 { bad = 1 } END { exit bad || !seen }' "$tmp/back.txt" \
  || fail "validation did not resume for good after snv_extrinsic came back: $(cat "$tmp/back.txt")"
# snv_extrinsic announces itself in NERV_HEALTH before its first normals, and from then on the
# validator waits for them: no frame goes out alone (until 2026-12-06 the first 2 did).
alone=$(awk '$5 == 0' "$tmp/back.txt" | wc -l)
((alone == 0)) || fail "$alone frames went out alone after snv_extrinsic came back: $(cat "$tmp/back.txt")"
if grep -q "missing_stixels" "$tmp/up.log"; then fail "normals taken for frames without STIXELS: $(grep missing_stixels "$tmp/up.log" | head -3)"; fi
pass "snv_extrinsic back, source counting from 0 again: all 10 frames validated, the first included"
no_survivors || fail "processes survived"
echo "2 passed, 0 failed"

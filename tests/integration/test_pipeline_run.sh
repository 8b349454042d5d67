#!/usr/bin/env bash
# The walking skeleton end to end: `tools/nerv run` starts the real lcm-logger
# and the four services on a private bus, plays a rendered sequence, and every
# frame comes out as DETECTIONS carrying the source's seq and utime.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"

data=$(synthetic_sequence urban 6)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

NERV_BUILD="$NERV_BUILD" "$NERV_ROOT/tools/nerv" run --data "$data" --out "$out" --rate 10 --timeout 20 \
  || fail "nerv run exited with $?"
[[ -s "$out/nerv.lcmlog" ]] || fail "no log written"
[[ -s "$out/summary.json" ]] || fail "no summary written"
no_survivors || fail "processes survived: $(pgrep -af "^$BIN/")"
pass "run completed, nothing left running"

# config/pipeline.yaml asks for a warm-up at the camera's size before the services subscribe
for s in stereo_matcher stixel snv_extrinsic; do
  grep -q "^$s: warmed up on a 1242x375 frame in" "$out/logs/services.log" \
    || fail "$s did not warm up: $(cat "$out/logs/services.log")"
done
pass "the services warmed up before the first frame"

"$BIN/nerv_export" "$out/nerv.lcmlog" --json --no-blobs >"$out/events.jsonl"
for ch in STEREO_FRAME DISPARITY STIXELS SURFACE_NORMALS EXTRINSICS DETECTIONS NERV_HEALTH; do
  grep -q "\"channel\":\"$ch\"" "$out/events.jsonl" || fail "channel $ch is not in the log"
done
pass "log holds every channel"

# seq and utime of every frame, as sent and as detected
frames=$(grep '"channel":"STEREO_FRAME"' "$out/events.jsonl" | grep -o '"header":{"seq":[0-9]*,"utime":[0-9]*' | sort -u)
dets=$(grep '"channel":"DETECTIONS"' "$out/events.jsonl" | grep -o '"header":{"seq":[0-9]*,"utime":[0-9]*' | sort -u)
[[ $(echo "$frames" | wc -l) -eq 6 ]] || fail "expected 6 frames in the log, got: $frames"
[[ "$frames" == "$dets" ]] || fail "DETECTIONS headers differ from STEREO_FRAME headers:\n$frames\nvs\n$dets"
pass "all 6 frames detected with the source's seq and utime"

grep '"channel":"NERV_HEALTH"' "$out/events.jsonl" >"$out/health.jsonl"
for s in "${SERVICES[@]}" source; do
  grep -q "\"service\":\"$s\"" "$out/health.jsonl" || fail "no NERV_HEALTH from $s"
done
pass "every service published NERV_HEALTH"

# Which build made the log: every process's health names the build its binary prints.
build=$("$BIN/stixel" --version | sed 's/^stixel: nerv //')
[[ "$build" =~ ^[0-9]+\.[0-9]+\.[0-9]+\ \(.+\)$ ]] || fail "stixel --version printed '$build'"
for s in "${SERVICES[@]}" source nerv_up; do
  binary=$s; [[ $s == source ]] && binary=nerv_source
  [[ "$("$BIN/$binary" --version)" == "$binary: nerv $build" ]] || fail "$binary --version: $("$BIN/$binary" --version)"
  grep "\"service\":\"$s\"" "$out/health.jsonl" | grep -F "\"version\":\"$build\"" >/dev/null \
    || fail "$s's health does not name the build $build: $(grep "\"service\":\"$s\"" "$out/health.jsonl" | tail -n1)"
done
grep -qF "\"version\":\"$build\"" "$out/summary.json" || fail "the summary does not name the build"
pass "every process reports the build nerv $build in its health, as --version prints it"

grep -q '"frames_in":6' "$out/summary.json" && grep -q '"frames_out":6' "$out/summary.json" \
  || fail "summary does not count 6 frames in and out: $(head -c 300 "$out/summary.json")"
# the latency breakdown covers every stage on every frame
for st in stereo_matcher stixel snv_extrinsic validator; do
  grep -Eq "\"$st\":\{\"frames\":6," "$out/summary.json" \
    || fail "latency breakdown lacks 6 frames of $st: $(grep -o '"latency_breakdown_ms".\{0,400\}' "$out/summary.json")"
done
# every frame says how much of its free space was measured (STIXELS.observed via DETECTIONS)
[[ $(grep -o '"strips":249' "$out/summary.json" | wc -l) -eq 6 ]] \
  || fail "summary lacks the free-space coverage of 6 frames: $(grep -o '"observed_share.\{0,60\}' "$out/summary.json" | head -3)"
# every stage reports its memory and CPU, and the summary follows each process's memory
for st in stereo_matcher stixel snv_extrinsic validator; do
  rss=$(tr -d '\n ' <"$out/summary.json" | grep -o "\"resources\":{.*" | grep -o "\"$st/0\":{[^}]*}" \
        | grep -o '"rss_last_mb":[^,}]*' | cut -d: -f2)
  awk -v r="$rss" 'BEGIN { exit !(r > 5 && r < 4096) }' \
    || fail "$st/0's memory in the summary's resources is '$rss' MiB: $(grep -o '"resources".\{0,300\}' "$out/summary.json")"
  grep "\"service\":\"$st\"" "$out/health.jsonl" | tail -n1 | grep -q '"gauge_names":\[[^]]*"cpu_percent","rss_mb","rss_peak_mb"' \
    || fail "$st's health lacks the process gauges: $(grep "\"service\":\"$st\"" "$out/health.jsonl" | tail -n1)"
done
"$BIN/nerv_export" "$out/nerv.lcmlog" --disparity-png "$out/disp" >/dev/null
[[ $(ls "$out/disp" | wc -l) -eq 6 ]] || fail "expected 6 disparity PNGs"
pass "summary and disparity export"
# The same frames with the disparity published as delta16 (common/delta16_codec.hpp):
# the stixel and snv services decode it, every frame is detected.
sed 's/^  output_encoding: u16le .*/  output_encoding: delta16/' "$NERV_ROOT/config/pipeline.yaml" >"$out/delta16.yaml"
grep -q '^  output_encoding: delta16' "$out/delta16.yaml" || fail "could not switch the config to delta16"
NERV_BUILD="$NERV_BUILD" "$NERV_ROOT/tools/nerv" run --data "$data" --out "$out/d16" --config "$out/delta16.yaml" \
  --rate 10 --timeout 20 >"$out/d16.log" 2>&1 || fail "nerv run with delta16 exited with $?: $(tail -n 3 "$out/d16.log")"
"$BIN/nerv_export" "$out/d16/nerv.lcmlog" --json --no-blobs >"$out/d16.jsonl"
[[ $(grep '"channel":"DISPARITY"' "$out/d16.jsonl" | grep -c '"encoding":"delta16"') -eq 6 ]] \
  || fail "expected 6 delta16 DISPARITY messages: $(grep -m1 '"channel":"DISPARITY"' "$out/d16.jsonl" | head -c 300)"
d16=$(grep '"channel":"DETECTIONS"' "$out/d16.jsonl" | grep -o '"header":{"seq":[0-9]*' | sort -u | wc -l)
[[ "$d16" -eq 6 ]] || fail "with delta16 $d16 of 6 frames were detected"
grep -q '"errors":[1-9]' "$out/d16/summary.json" && fail "errors with delta16: $(grep -o '"health".\{0,400\}' "$out/d16/summary.json")"
pass "the pipeline runs on delta16 disparity, all 6 frames detected"
echo "1 passed, 0 failed"

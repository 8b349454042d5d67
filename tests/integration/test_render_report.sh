#!/usr/bin/env bash
# nerv_render and nerv_report on a real pipeline log: a short synthetic run
# through the four services, then
#  - one PNG per frame of the expected size, with the kept boxes of DETECTIONS
#    drawn at their pixels (checked by test_render_overlay against this log),
#    and an MJPG AVI;
#  - bad input (missing log, a file that is no log) ends with one line, no crash;
#  - the HTML report opened in headless Chromium: every <img> a data: URI that
#    decodes to a JPEG, every plot an inline <svg>, a screenshot that is not blank.
# Without the `chromium` package the browser part is skipped (exit 77).
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"

data=$(synthetic_sequence urban 6)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

NERV_BUILD="$NERV_BUILD" "$NERV_ROOT/tools/nerv" run --data "$data" --out "$out/run" --rate 10 --timeout 20 \
  >"$out/run.txt" 2>&1 || fail "nerv run exited with $?: $(tail -n 3 "$out/run.txt")"
log="$out/run/nerv.lcmlog"

# --- render ------------------------------------------------------------------
"$BIN/nerv_render" "$log" --out "$out/render" --video --labels "$data/label_2" >"$out/render.txt" 2>&1 \
  || fail "nerv_render exited with $?: $(cat "$out/render.txt")"
png_size() {  # prints "W H" from a PNG's IHDR
  od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8}'
}
read -r W H < <(png_size "$data/image_2/000000.png")
n=0
for i in 0 1 2 3 4 5; do
  f="$out/render/$(printf %06d "$i").png"
  [[ -s "$f" ]] || fail "no image $f"
  [[ "$(png_size "$f")" == "$((2 * W)) $((3 * (H + 26)))" ]] || fail "$f is $(png_size "$f"), expected $((2 * W)) $((3 * (H + 26)))"
  n=$((n + 1))
done
pass "$n frames rendered at $((2 * W))x$((3 * (H + 26))) (panels of ${W}x${H})"
[[ "$(head -c 4 "$out/render/render.avi")" == RIFF && "$(od -An -c -j8 -N4 "$out/render/render.avi" | tr -d ' ')" == AVI ]] \
  || fail "render.avi is not a RIFF AVI"
frames=$(od -An -tu4 -j48 -N4 "$out/render/render.avi" | tr -d ' ')
[[ "$frames" == 6 ]] || fail "render.avi holds $frames frames, expected 6"
pass "MJPG AVI with 6 frames"

NERV_RENDER_LOG="$log" NERV_RENDER_DIR="$out/render" "$NERV_BUILD/tests/test_render_overlay" \
  --gtest_filter=renderOverlay.PipelineLogBoxesAtTheirPixels >"$out/boxes.txt" 2>&1 \
  || fail "boxes not at their pixels: $(grep -E 'Failure|is ' "$out/boxes.txt" | head -n 6)"
grep -q '^\[  PASSED  \] 1 test' "$out/boxes.txt" || fail "box check did not run: $(tail -n 3 "$out/boxes.txt")"
pass "$(grep -o 'checked .*' "$out/boxes.txt")"

# --- bad input ---------------------------------------------------------------
rc=0; "$BIN/nerv_render" "$out/missing.lcmlog" --out "$out/bad" 2>"$out/err.txt" || rc=$?
[[ $rc == 2 && $(wc -l <"$out/err.txt") == 1 ]] || fail "missing log: exit $rc, '$(cat "$out/err.txt")'"
head -c 100000 /dev/urandom >"$out/noise.lcmlog"
rc=0; "$BIN/nerv_render" "$out/noise.lcmlog" --out "$out/bad" 2>"$out/err.txt" || rc=$?
[[ $rc == 1 ]] && grep -q "no STEREO_FRAME" "$out/err.txt" || fail "noise log: exit $rc, '$(cat "$out/err.txt")'"
head -c 1500000 "$log" >"$out/cut.lcmlog"  # a log cut in the middle of a message
rc=0; "$BIN/nerv_render" "$out/cut.lcmlog" --out "$out/cut" >"$out/err.txt" 2>&1 || rc=$?
((rc < 2)) || fail "cut log: exit $rc, $(cat "$out/err.txt")"
rc=0; "$BIN/nerv_report" "$out/noise.lcmlog" --out "$out/noise_report" >"$out/err.txt" 2>&1 || rc=$?
[[ $rc == 0 && -s "$out/noise_report/report.html" ]] || fail "report of a noise log: exit $rc, $(cat "$out/err.txt")"
pass "missing, noise and cut logs end with one line, no crash"

# --- report ------------------------------------------------------------------
"$BIN/nerv_report" "$log" --labels "$data/label_2" --out "$out/report" >"$out/report.txt" 2>&1 \
  || fail "nerv_report exited with $?: $(cat "$out/report.txt")"
html="$out/report/report.html"
[[ -s "$html" ]] || fail "no report.html"
grep -q 'stixel + SNV (kept)' "$html" || fail "no precision/recall table in the report"
grep -q 'Distance of the kept detections' "$html" && grep -q '<td>nearest_z_m</td>' "$html" \
  || fail "no distance table in the report (6 urban frames have fully visible cars)"
# The uncertainty of the nearest depth came over the bus with each detection
# (stixel -> roi_t -> validator -> detection_t.nearest_z_sigma_m): the report
# compares the errors with it.
grep -q '<th>within 1 sigma</th>' "$html" \
  && grep -Eq '<td>nearest_z_m</td>(<td[^>]*>[^<]*</td>){6}<td[^>]*>[0-9]+ %</td><td[^>]*>[0-9]+ %</td>' "$html" \
  || fail "the distance table has no share within the detections' nearest_z_sigma_m"
grep -q 'Why objects were missed' "$html" \
  && { grep -q 'No labelled object was missed' "$html" || grep -q '<th>by class (stixel + SNV)</th>' "$html"; } \
  || fail "no misses-by-cause section in the report"
grep -q 'Free or unseen (STIXELS.observed)' "$html" \
  && grep -Eq 'free space measured, median / lowest frame \[%\]</td><td>[0-9]+ / [0-9]+<' "$html" \
  || fail "no free-space coverage in the report"
if grep -Eq '<(script|link)[ >]|src="http|url\(http' "$html"; then fail "the report refers to something outside itself"; fi
pass "report written: $(cat "$out/report.txt")"

command -v chromium >/dev/null || { echo "SKIP: chromium is not installed (the browser check needs it)" >&2; exit 77; }
browse() {  # browse ARGS...: headless Chromium on the report, private profile
  local profile; profile=$(mktemp -d -p "$out")
  timeout 90 chromium --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run --user-data-dir="$profile" "$@" "file://$html"
}
browse --dump-dom >"$out/dom.html" 2>"$out/chromium.log" || fail "chromium --dump-dom failed: $(tail -n 3 "$out/chromium.log")"
grep -q '</html>' "$out/dom.html" || fail "chromium returned no document"
imgs=$(grep -o '<img [^>]*>' "$out/dom.html" | wc -l)
((imgs >= 2)) || fail "expected at least 2 images in the report, found $imgs"
i=0
while read -r src; do
  i=$((i + 1))
  [[ "$src" == data:image/jpeg\;base64,* ]] || fail "image $i is not an inline JPEG: ${src:0:40}"
  printf %s "${src#*,}" | base64 -d >"$out/img$i.jpg" 2>/dev/null || fail "image $i is not valid base64"
  magic=$(od -An -tx1 -N3 "$out/img$i.jpg" | tr -d ' ')
  tail_bytes=$(tail -c 2 "$out/img$i.jpg" | od -An -tx1 | tr -d ' ')
  [[ "$magic" == ffd8ff && "$tail_bytes" == ffd9 ]] || fail "image $i does not decode to a whole JPEG ('$magic'...'$tail_bytes')"
done < <(grep -o '<img [^>]*>' "$out/dom.html" | grep -o 'src="[^"]*"' | sed 's/^src="//; s/"$//')
svgs=$(grep -o '<svg [^>]*class="plot"' "$out/dom.html" | wc -l)
((svgs >= 7)) || fail "expected at least 7 plots, found $svgs"
pass "browser DOM: $imgs inline images that decode, $svgs SVG plots"

browse --screenshot="$out/shot.png" --window-size=1400,3000 >/dev/null 2>>"$out/chromium.log" \
  || fail "chromium --screenshot failed: $(tail -n 3 "$out/chromium.log")"
[[ "$(png_size "$out/shot.png")" == "1400 3000" ]] || fail "screenshot is $(png_size "$out/shot.png")"
# A blank 1400x3000 page compresses to a few kB; plots, text and photos do not.
bytes=$(stat -c %s "$out/shot.png")
((bytes > 60000)) || fail "screenshot looks blank ($bytes bytes)"
pass "screenshot 1400x3000, $bytes bytes"
echo "1 passed, 0 failed"

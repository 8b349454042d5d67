#!/usr/bin/env bash
# The rig's corrections kept across restarts (services/stereo_matcher/rig_state.hpp), through the
# four real services with stereo_matcher.rig_state_file set. The KITTI 0926 frames (the synthetic
# urban sequence when ../shared/data is absent) with the right views a row down (nerv_misalign):
#  - the first run corrects from the 11th frame, as without the file, and writes the file (rows
#    about 1 px, the calibration's fingerprint);
#  - the second run restores it at its first frame: said in the log, counted in NERV_HEALTH
#    (rig_state_restored), and its first verdict (10th frame) finds what the matcher saw of the
#    rows already under 0.2 px: frames 1-10 were matched corrected. The file is not rewritten;
#  - the same frames with another calibration (cx one pixel over): the file is said to be of
#    another calibration and not used; the first verdict sets the correction again and replaces it;
#  - a file that is not a rig state: the error bad_rig_state names it, every frame still comes out;
#  - the case it is for: under one nerv_up, the stereo_matcher killed after it saved its correction
#    is restarted by nerv_up and corrects from its first frame again.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT

data=$(kitti_or_synthetic)
"$BIN/nerv_misalign" --data "$data" --out "$tmp/moved" --rows 1 >/dev/null || fail "nerv_misalign --rows 1"

state="$tmp/rig state.yaml"  # a space in the path on purpose
sed "s|^stereo_matcher:\$|stereo_matcher:\n  rig_state_file: \"$state\"|" "$NERV_ROOT/config/pipeline.yaml" >"$tmp/kept.yaml"
grep -q "^  rig_state_file: " "$tmp/kept.yaml" || fail "could not set rig_state_file in the config"

run() { run_pipeline "$1" "$2" --config "$tmp/kept.yaml" --repeat 2 --rate 10; }  # 2 x at 10 Hz, the state kept
matcher_value() {  # matcher_value NAME KEY: errors (summary.json) or a counter of the stereo_matcher's last NERV_HEALTH
  if [[ "$2" == errors ]]; then matcher_field "$1" errors; return; fi
  [[ -f "$tmp/$1.jsonl" ]] || "$BIN/nerv_export" "$tmp/$1/nerv.lcmlog" --json --no-blobs >"$tmp/$1.jsonl"
  local h names values i
  h=$(grep '"channel":"NERV_HEALTH"' "$tmp/$1.jsonl" | grep '"service":"stereo_matcher"' | tail -n 1)
  names=$(grep -o '"counter_names":\[[^]]*\]' <<<"$h" | sed 's/.*\[//; s/\]//; s/"//g' | tr ',' '\n')
  values=$(grep -o '"counter_values":\[[^]]*\]' <<<"$h" | sed 's/.*\[//; s/\]//' | tr ',' '\n')
  i=$(grep -nx "$2" <<<"$names" | cut -d: -f1)
  [[ -n "$i" ]] && sed -n "${i}p" <<<"$values"
}
frames_out() { echo "$(matcher_field "$1" frames_in) $(matcher_field "$1" frames_out)"; }  # "IN OUT" of the stereo_matcher
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { exit !(a - b <= t && b - a <= t) }'; }

# First run: no file yet; written at the first verdict's correction.
run first "$tmp/moved"
log="$tmp/first/logs/services.log"
grep -q "rig state: .* does not exist yet" "$log" || fail "first run: no 'does not exist yet' line: $(grep 'rig state' "$log")"
[[ -f "$state" ]] || fail "first run: $state not written: $(grep -i 'rig.state\|row_misaligned' "$log" | head -n 3)"
offset=$(sed -n 's/^  offset_px: //p' "$state")
near "$offset" 1 0.15 || fail "first run: the saved row correction is '$offset', not about 1: $(cat "$state")"
grep -q '^  fingerprint: "[0-9a-f]\{16\}"$' "$state" || fail "first run: no fingerprint in $(cat "$state")"
[[ "$(matcher_value first rig_state_saved)" == 1 ]] || fail "first run: rig_state_saved is '$(matcher_value first rig_state_saved)'"
first_verdict=$(grep "row_misaligned" "$log" | head -n 1)
[[ "$first_verdict" == *"from the next frame the stereo_matcher resamples its right views"* ]] \
  || fail "first run: the first verdict set no correction: '$first_verdict'"
cp "$state" "$tmp/saved_copy.yaml"
pass "first run: corrected from frame $(sed -E 's/.*frame ([0-9]+): .*/\1/' <<<"$first_verdict") and saved (offset_px $offset)"

# Second run, the same rig: corrected from its first frame.
run second "$tmp/moved"
log="$tmp/second/logs/services.log"
line=$(grep "rig state: from the first frame" "$log" | head -n 1)
[[ -n "$line" ]] || fail "second run: nothing restored: $(grep 'rig state' "$log")"
[[ "$(matcher_value second rig_state_restored)" == 1 ]] || fail "second run: rig_state_restored is '$(matcher_value second rig_state_restored)'"
verdict=$(grep "row_misaligned" "$log" | head -n 1)
left=$(sed -E 's/.*which leaves up to ([0-9.]+) px.*/\1/' <<<"$verdict")
awk -v l="$left" 'BEGIN { exit !(l < 0.2) }' || fail "second run: the first verdict: '$verdict'"
grep -q "resamples its right views by" <<<"$verdict" && fail "second run: the first verdict set the correction anew: '$verdict'"
cmp -s "$state" "$tmp/saved_copy.yaml" || fail "second run: the file was rewritten without a change: $(diff "$tmp/saved_copy.yaml" "$state")"
read -r in out <<<"$(frames_out second)"
[[ "$in" == "$out" && "$in" -gt 0 ]] || fail "second run: $in in, $out out"
pass "second run: ${line#*rig state: }; first verdict at frame $(sed -E 's/.*frame ([0-9]+): .*/\1/' <<<"$verdict") leaves $left px"

# Another calibration: cx one pixel over.
mkdir -p "$tmp/recal"
ln -s "$tmp/moved/left" "$tmp/recal/left"
ln -s "$tmp/moved/right" "$tmp/recal/right"
awk '/^cx:/ { $2 = $2 + 1 } { print }' "$tmp/moved/calib.yaml" >"$tmp/recal/calib.yaml"
run recal "$tmp/recal"
log="$tmp/recal/logs/services.log"
line=$(grep "rig state: .* is of another calibration" "$log" | head -n 1)
[[ "$line" == *"(cx "*" against "*"): not used"* ]] || fail "recalibrated: '$line' $(grep 'rig state' "$log")"
[[ "$(matcher_value recal rig_state_other_calibration)" == 1 ]] || fail "recalibrated: counter rig_state_other_calibration missing"
grep -q "rig state: from the first frame" "$log" && fail "recalibrated: restored all the same"
cmp -s "$state" "$tmp/saved_copy.yaml" && fail "recalibrated: the file was not replaced at the first correction"
pass "recalibrated rig: ${line#*rig state: }"

# Not a rig state: an error, and the frames go through uncorrected until the first verdict.
echo "row_correction: {offset_px: 1.0}" >"$state"
run bad "$tmp/moved"
log="$tmp/bad/logs/services.log"
line=$(grep "bad_rig_state" "$log" | head -n 1)
[[ "$line" == *"rig state file $state: key 'calibration.fingerprint' is missing; not used"* ]] \
  || fail "bad file: '$line' $(grep 'rig state' "$log")"
(( $(matcher_value bad errors) >= 1 )) || fail "bad file: NERV_HEALTH counts no error"
read -r in out <<<"$(frames_out bad)"
[[ "$in" == "$out" && "$in" -gt 0 ]] || fail "bad file: $in in, $out out"
pass "a file that is not a rig state: ${line#*bad_rig_state: }"

# Killed and restarted under nerv_up: the restarted matcher picks the correction up at its first frame.
rm -f "$state"
start_child "$tmp/up.log" "$BIN/nerv_up" --config "$tmp/kept.yaml" --lcm-url "$URL" --quiet
"$BIN/nerv_source" --data "$tmp/moved" --repeat 2 --rate 10 --lcm-url "$URL" --drain-timeout 20 \
  --wait-for stereo_matcher,stixel,snv_extrinsic,validator 2>"$tmp/source1.log" || fail "before the kill: $(tail -c 300 "$tmp/source1.log")"
[[ -f "$state" ]] || fail "under nerv_up: nothing saved: $(grep -i 'rig state\|row_misaligned' "$tmp/up.log" | head -n 3)"
victim=$(nerv_pgrep "stereo_matcher ") || fail "no stereo_matcher under nerv_up"
kill -KILL "$victim"
wait_until 20 bash -c "$(declare -f pgrep_program nerv_pgrep); BIN='$BIN'; nerv_pgrep 'stereo_matcher ' | grep -vx $victim" >/dev/null || fail "the stereo_matcher was not restarted: $(tail -n 5 "$tmp/up.log")"
"$BIN/nerv_source" --data "$tmp/moved" --rate 10 --lcm-url "$URL" --drain-timeout 20 \
  --wait-for stereo_matcher,stixel,snv_extrinsic,validator 2>"$tmp/source2.log" || fail "after the kill: $(tail -c 300 "$tmp/source2.log")"
line=$(grep "rig state: from the first frame" "$tmp/up.log" | head -n 1)
[[ -n "$line" ]] || fail "the restarted stereo_matcher restored nothing: $(grep -i 'rig state\|restart' "$tmp/up.log" | head -n 5)"
pass "killed and restarted by nerv_up: ${line#*rig state: }"
echo "5 passed, 0 failed"

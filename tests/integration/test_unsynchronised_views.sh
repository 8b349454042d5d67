#!/usr/bin/env bash
# A rig whose shutters are not triggered together: the rendered urban street (ego at 8 m/s,
# 10 frames a second) with each right view taken 10 ms after its left (nerv_synth
# --right-delay-ms), played twice through the four services with the default config. The real
# stereo_matcher compares each checked pair with the frame before (shutter_sync.hpp):
#  - delayed: the error views_unsynchronised in the log and in NERV_HEALTH, naming a delay
#    of 10 +- 3 ms with the right view after the left (also as NERV_HEALTH's gauge
#    view_delay_ms), and every frame still comes out;
#  - the same street rendered with the views together: "synchronised" in the log, no error.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT

run() {  # run NAME DATA: 2 x the sequence at 10 Hz through the four services, default config
  "$NERV_ROOT/tools/nerv" run --data "$2" --repeat 2 --rate 10 --out "$tmp/$1" \
    >"$tmp/$1.txt" 2>&1 || fail "$1: nerv run exited with $?: $(tail -n 3 "$tmp/$1.txt")"
}
field() {  # field NAME KEY: the stereo_matcher's KEY in summary.json
  tr -d '\n ' <"$tmp/$1/summary.json" | grep -o '"stereo_matcher/0":{[^}]*}' | grep -o "\"$2\":[^,}]*" | cut -d: -f2-
}

"$BIN/nerv_synth" --scene urban --frames 12 --out "$tmp/late" --right-delay-ms 10 --quiet >/dev/null 2>&1 \
  || fail "nerv_synth --right-delay-ms 10"
run late "$tmp/late"
line=$(grep "views_unsynchronised" "$tmp/late/logs/services.log" | head -n 1)
[[ -n "$line" ]] || fail "no views_unsynchronised error: $(grep -i 'shutter\|rectification' "$tmp/late/logs/services.log" | head -n 5)"
delay=$(sed -E 's/.*the right view is taken ([0-9.]+) ms (after|before) the left.*/\1 \2/' <<<"$line")
read -r ms side <<<"$delay"
awk -v m="$ms" 'BEGIN { exit !(m >= 7 && m <= 13) }' && [[ "$side" == after ]] \
  || fail "10 ms late read as '$delay': '$line'"
(( $(field late errors) >= 1 )) || fail "NERV_HEALTH of the stereo_matcher counts no error"
tr -d '\n ' <"$tmp/late/summary.json" | grep '"last_error":"views_unsynchronised:frame[0-9]*:shutters' >/dev/null \
  || fail "NERV_HEALTH's last_error is not the shutters: $(field late last_error)"
gauge=$(field late view_delay_ms)
awk -v g="$gauge" 'BEGIN { exit !(g >= 7 && g <= 13) }' || fail "NERV_HEALTH's gauge view_delay_ms is '$gauge'"
in=$(field late frames_in) out=$(field late frames_out)
[[ "$in" == 24 && "$out" == 24 ]] || fail "frames lost: $in in, $out out"
pass "right view 10 ms late: ${line#*views_unsynchronised: }; $out of $in frames out"

together=$(synthetic_sequence urban 20)
run together "$together"
line=$(grep "shutter check" "$tmp/together/logs/services.log" | head -n 1)
[[ "$line" == *": synchronised" ]] || fail "no 'synchronised' line for views taken together: '$line'"
grep -q views_unsynchronised "$tmp/together/logs/services.log" && fail "views taken together called unsynchronised"
pass "views taken together: ${line#*shutter check: }"
echo "2 passed, 0 failed"

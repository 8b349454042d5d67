#!/usr/bin/env bash
# Bad input gets a clear one-line error and loses nothing:
#  - malformed messages are counted in NERV_HEALTH and the services keep running; a message of
#    another layout (an older build's) is named as such, and an older build's NERV_HEALTH is read;
#  - a missing data folder, a missing calibration or an unknown config key end
#    the command with one line and a non-zero exit, with no process left.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT

# 1. malformed messages over the bus
start_child "$tmp/stereo.log" "$BIN/stereo_matcher" --lcm-url "$URL"
start_child "$tmp/stixel.log" "$BIN/stixel" --lcm-url "$URL"
"$BIN/nerv_test_inject" "$URL" || { cat "$tmp"/*.log; fail "rejections not counted"; }
for pid in "${CHILDREN[@]}"; do kill -0 "$pid" || fail "a service died on bad input"; done
grep -q "stereo_matcher: bad_size" "$tmp/stereo.log" || fail "no one-line error for bad_size: $(cat "$tmp/stereo.log")"
grep -q "does not decode as disparity_t: its layout (fingerprint [0-9a-f]*) is not this build's" "$tmp/stixel.log" \
  || fail "a DISPARITY of another layout not named as such: $(grep decode_failed "$tmp/stixel.log")"
grep -q "another stixel/0 runs on host old-pc, pid 4242" "$tmp/stixel.log" \
  || fail "an older build's NERV_HEALTH not read: $(grep -i duplicate "$tmp/stixel.log")"
stop_children
pass "malformed messages counted, services alive; another build's layout named, its NERV_HEALTH read"

# 2. unknown config key: one line naming it, exit 2
printf 'stixel:\n  colum_width_px: 3\n' >"$tmp/bad.yaml"
set +e
msg=$("$BIN/stixel" --config "$tmp/bad.yaml" --lcm-url "$URL" 2>&1); rc=$?
set -e
[[ $rc -eq 2 ]] || fail "unknown key: exit $rc"
[[ "$msg" == "stixel: unknown config key 'stixel.colum_width_px'" ]] || fail "unknown key message: $msg"
pass "unknown config key: $msg"

# 3. the nerv command: missing data folder, missing calibration, unknown key
set +e
msg=$("$NERV_ROOT/tools/nerv" run --data "$tmp/nope" --out "$tmp/o1" 2>&1); rc=$?
[[ $rc -ne 0 && $(echo "$msg" | wc -l) -eq 1 && "$msg" == *"does not exist"* ]] || fail "missing data: rc $rc: $msg"
mkdir -p "$tmp/nocalib/left" "$tmp/nocalib/right"
msg=$("$NERV_ROOT/tools/nerv" run --data "$tmp/nocalib" --out "$tmp/o2" 2>&1); rc=$?
[[ $rc -ne 0 && "$msg" == *"calib.yaml is missing"* ]] || fail "missing calibration: rc $rc: $msg"
data=$(synthetic_sequence urban 6)
msg=$("$NERV_ROOT/tools/nerv" run --data "$data" --out "$tmp/o3" --config "$tmp/bad.yaml" 2>&1); rc=$?
set -e
[[ $rc -ne 0 && "$msg" == *"unknown config key 'stixel.colum_width_px'"* ]] || fail "unknown key via run: rc $rc: $msg"
wait_until 5 no_survivors || fail "processes survived: $(pgrep -af "^$BIN/")"
pass "command-line errors are one line, nothing left running"
echo "1 passed, 0 failed"

#!/usr/bin/env bash
# Free or unseen: the real stixel, snv_extrinsic and validator processes get a
# rendered road seen whole and then mostly blinded (no disparity). STIXELS and
# DETECTIONS must say how much of the free space was measured, the blinded
# frame must read as unknown (120 of 249 strips unobserved), the car beside the
# blinded part must still be proposed, and NERV_HEALTH must count the frame.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT

for s in stixel snv_extrinsic validator; do start_child "$tmp/$s.log" "$BIN/$s" --lcm-url "$URL"; done
"$BIN/nerv_test_inject_blind" "$URL" || { tail -n 5 "$tmp"/*.log; fail "the blinded view was not reported"; }
grep -q "stixel: unobserved" "$tmp/stixel.log" || fail "no one-line error for the blinded frame: $(cat "$tmp/stixel.log")"
grep "stixel: unobserved" "$tmp/stixel.log" | head -1
for pid in "${CHILDREN[@]}"; do kill -0 "$pid" || fail "a service died"; done
stop_children
pass "blinded view reported as unobserved on STIXELS, DETECTIONS and NERV_HEALTH"
echo "1 passed, 0 failed"

#!/usr/bin/env bash
# Three vehicle computers on one machine: network namespaces joined by veth
# pairs and a bridge (10.77.0.0/24, multicast routed to the veth, ttl=1).
#   host1 (camera):     source + stereo_matcher
#   host2 (perception): stixel + snv_extrinsic
#   host3 (planner):    validator + lcm-logger
# Every frame must come out detected and logged. Then the perception computer's
# link goes down for a second (a loose connector, a switch restarting): the
# services keep running and the next frames cross again. All traffic stays inside
# the namespaces this test creates.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
command -v ip >/dev/null || { echo "SKIP: iproute2 missing"; exit 77; }
data=$(synthetic_sequence urban 6)
tmp=$(mktemp -d)
tag="nerv$$"
HOSTS=("${tag}h1" "${tag}h2" "${tag}h3")
cleanup() {
  for h in "${HOSTS[@]}"; do
    for pid in $(ip netns pids "$h" 2>/dev/null); do kill -TERM "$pid" 2>/dev/null || true; done
  done
  stop_children
  for h in "${HOSTS[@]}"; do
    for pid in $(ip netns pids "$h" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
    ip netns del "$h" 2>/dev/null || true
  done
  ip link del br77 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT

# The bridge lives in this test's private namespace (the "switch").
ip link add br77 type bridge mcast_snooping 0 || { echo "SKIP: cannot create a bridge"; exit 77; }
ip link set br77 up
for i in 1 2 3; do
  h=${HOSTS[$((i - 1))]}
  ip netns add "$h" || { echo "SKIP: cannot create named network namespaces"; exit 77; }
  ip link add "v${i}${tag}" type veth peer name eth0 netns "$h"
  ip link set "v${i}${tag}" master br77 up
  ip netns exec "$h" ip link set lo up
  ip netns exec "$h" ip addr add "10.77.0.$i/24" dev eth0
  ip netns exec "$h" ip link set eth0 up multicast on
  ip netns exec "$h" ip route add 224.0.0.0/4 dev eth0
done
URL2="udpm://239.255.76.67:7667?ttl=1&recv_buf_size=4194304"
on() { local h=${HOSTS[$(($1 - 1))]}; shift; ip netns exec "$h" "$@"; }

start_child "$tmp/logger.log" ip netns exec "${HOSTS[2]}" lcm-logger --lcm-url="$URL2" -f -q "$tmp/nerv.lcmlog"
start_child "$tmp/stereo.log" ip netns exec "${HOSTS[0]}" "$BIN/stereo_matcher" --lcm-url "$URL2"
start_child "$tmp/stixel.log" ip netns exec "${HOSTS[1]}" "$BIN/stixel" --lcm-url "$URL2"
start_child "$tmp/snv.log" ip netns exec "${HOSTS[1]}" "$BIN/snv_extrinsic" --lcm-url "$URL2"
start_child "$tmp/validator.log" ip netns exec "${HOSTS[2]}" "$BIN/validator" --lcm-url "$URL2"

# The source on host1 waits until it hears every service's health across the bridge.
on 1 "$BIN/nerv_source" --data "$data" --rate 5 --lcm-url "$URL2" --drain-timeout 20 \
  --wait-for stereo_matcher,stixel,snv_extrinsic,validator 2>"$tmp/source.log" \
  || { cat "$tmp"/*.log; fail "not every frame came out as DETECTIONS across hosts"; }
pass "$(tail -n1 "$tmp/source.log")"

# host2's link down and up again; the kernel drops its multicast route with the link,
# so it comes back as a network manager would bring it back.
on 2 ip link set eth0 down
sleep 1
on 2 ip link set eth0 up multicast on
on 2 ip route add 224.0.0.0/4 dev eth0
on 1 "$BIN/nerv_source" --data "$data" --rate 5 --lcm-url "$URL2" --drain-timeout 20 \
  --wait-for stereo_matcher,stixel,snv_extrinsic,validator 2>"$tmp/source2.log" \
  || { cat "$tmp"/*.log; fail "after host2's link came back, not every frame came out as DETECTIONS"; }
for svc in stixel snv_extrinsic; do
  nerv_pgrep "$svc " >/dev/null || fail "$svc on host2 did not survive its link going down"
done
pass "host2's link down for 1 s and up again: the same services detect the next 6 frames too"
sleep 0.3
stop_children

"$BIN/nerv_export" "$tmp/nerv.lcmlog" --summary "$tmp/summary.json" >/dev/null
grep -q '"frames_in":6' "$tmp/summary.json" && grep -q '"frames_out":6' "$tmp/summary.json" \
  || fail "the logger on host3 did not record all 6 frames: $(head -c 300 "$tmp/summary.json")"
# Both runs of the 6 frames (the summary counts each seq once).
"$BIN/nerv_export" "$tmp/nerv.lcmlog" --json --no-blobs >"$tmp/all.jsonl"
for ch in STEREO_FRAME DETECTIONS; do
  n=$(grep -c "\"channel\":\"$ch\"" "$tmp/all.jsonl" || true)
  [[ "$n" -eq 12 ]] || fail "host3's logger recorded $n $ch messages, expected 12 (two runs of 6)"
done
grep '"channel":"NERV_HEALTH"' "$tmp/all.jsonl" >"$tmp/health.jsonl" || true
for s in stereo_matcher stixel snv_extrinsic validator; do
  grep -q "\"service\":\"$s\"" "$tmp/health.jsonl" || fail "no health from $s in the log"
done
pass "host3's lcm-logger recorded all 12 frames and every service's health"
echo "3 passed, 0 failed"

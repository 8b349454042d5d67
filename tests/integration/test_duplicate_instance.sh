#!/usr/bin/env bash
# Two processes of the same stage and instance on one bus (started by hand beside a
# supervisor's, or two supervisors) both process every frame and publish it twice.
# Each says so once, naming the other: an error in its log and its NERV_HEALTH.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT

start_child "$tmp/a.log" "$BIN/stixel" --lcm-url "$URL"
first=${CHILDREN[-1]}
start_child "$tmp/b.log" "$BIN/stixel" --lcm-url "$URL"
second=${CHILDREN[-1]}
host=$(hostname)
wait_until 20 grep -q "duplicate_instance: another stixel/0 runs on host $host, pid $second:" "$tmp/a.log" \
  || fail "the first stixel did not notice the second: $(cat "$tmp/a.log")"
wait_until 20 grep -q "duplicate_instance: another stixel/0 runs on host $host, pid $first:" "$tmp/b.log" \
  || fail "the second stixel did not notice the first: $(cat "$tmp/b.log")"
wait_until 10 bash -c "'$BIN/nerv_up' --status --listen 1.5 | grep -q '^stixel/0 .*errors 1 .*last: duplicate_instance: another stixel/0'" \
  || fail "NERV_HEALTH does not carry it: $("$BIN/nerv_up" --status --listen 1.5)"
sleep 2.5  # more reports from the other: still one error each
for f in a b; do
  n=$(grep -c "duplicate_instance" "$tmp/$f.log" || true)
  [[ "$n" -eq 1 ]] || fail "stixel $f reported the same twin $n times: $(cat "$tmp/$f.log")"
done
pass "two stixel/0 on one bus: each named the other once ($(grep -o 'another stixel/0 runs on host [^:]*' "$tmp/a.log"))"

# A shard of another instance name is no twin.
start_child "$tmp/c.log" "$BIN/stixel" --lcm-url "$URL" --shard 1/2
wait_until 20 bash -c "'$BIN/nerv_up' --status --listen 1.5 | grep -q '^stixel/shard1 '" || fail "the shard does not report"
sleep 1.5
if grep -q "duplicate_instance" "$tmp/c.log"; then fail "a shard was taken for a twin: $(cat "$tmp/c.log")"; fi
pass "stixel/shard1 beside them is not taken for a twin"
stop_children
no_survivors || fail "processes survived"
echo "2 passed, 0 failed"

#!/usr/bin/env bash
# A hung service is restarted: a process that still exists but has stopped sending
# NERV_HEALTH (kill -STOP here; a deadlock or a frame it never finishes in a car) is
# killed by nerv_up's watchdog and started again, and a pipeline at work is never
# taken for hung. nerv_up's own NERV_HEALTH says how often and why it restarted what, and a
# service that dies of SIGILL is named as a build for another CPU.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT
data=$(synthetic_sequence urban 6)
cp "$NERV_ROOT/config/pipeline.yaml" "$tmp/watchdog.yaml"
printf 'run:\n  watchdog_s: 2\n' >>"$tmp/watchdog.yaml"

# 1. Busy, not hung: 18 frames at 10 Hz through all four services under a 2 s watchdog.
"$NERV_ROOT/tools/nerv" run --data "$data" --repeat 3 --out "$tmp/busy" --config "$tmp/watchdog.yaml" \
  --rate 10 >"$tmp/busy.txt" 2>&1 || fail "run under the watchdog: $(tail -3 "$tmp/busy.txt")"
if grep -q "sent no health" "$tmp/busy/logs/services.log"; then
  fail "a working service was taken for hung: $(grep "sent no health" "$tmp/busy/logs/services.log")"
fi
pass "18 frames through four services, none taken for hung by a 2 s watchdog"
host=$(hostname)
"$BIN/nerv_export" "$tmp/busy/nerv.lcmlog" --json --no-blobs | grep '"channel":"NERV_HEALTH"' \
  | grep '"service":"nerv_up"' >"$tmp/up_health.jsonl" || fail "the log holds no NERV_HEALTH of nerv_up"
grep -q "\"instance\":\"$host\",\"host\":\"$host\"" "$tmp/up_health.jsonl" || fail "nerv_up's report is not named by its host"
if grep -q '"errors":[1-9]' "$tmp/up_health.jsonl"; then fail "nerv_up reported restarts: $(tail -n1 "$tmp/up_health.jsonl")"; fi
pass "the log holds nerv_up's own reports ($(wc -l <"$tmp/up_health.jsonl")), no restart in them"

# 2. Hung: stop the validator, keep the stixel stage running beside it.
reports() {  # reports SERVICE PID: that process is on the health board and not silent
  "$BIN/nerv_up" --status --listen 1.5 2>/dev/null | grep -Eq "^$1/0 +pid $2 +(ok|idle) "
}
start_child "$tmp/up.log" "$BIN/nerv_up" --config "$tmp/watchdog.yaml" --services stixel,validator --quiet
for svc in validator stixel; do
  wait_until 30 nerv_pgrep "$svc " >/dev/null || fail "$svc never started: $(cat "$tmp/up.log")"
done
victim=$(nerv_pgrep "validator ")
bystander=$(nerv_pgrep "stixel ")
wait_until 30 reports validator "$victim" || fail "validator $victim never reported health"
kill -STOP "$victim"
wait_until 20 grep -q "validator/0 (pid $victim) sent no health" "$tmp/up.log" \
  || fail "the stopped validator was not taken for hung: $(cat "$tmp/up.log")"
wait_until 10 bash -c "! kill -0 $victim 2>/dev/null" || fail "the hung validator $victim is still there"
wait_until 20 grep -q "restarted validator/0" "$tmp/up.log" || fail "validator not restarted: $(cat "$tmp/up.log")"
# Restarted like a crashed service, after the first back-off (restart_backoff_s 0.5).
grep -q "validator/0 (pid $victim) killed by signal 9 (hung); restart in 0.5 s" "$tmp/up.log" \
  || fail "not restarted after the first back-off: $(grep "pid $victim" "$tmp/up.log")"
fresh=$(nerv_pgrep "validator ")
[[ -n "$fresh" && "$fresh" != "$victim" ]] || fail "no new validator process ($fresh)"
wait_until 30 reports validator "$fresh" || fail "the restarted validator $fresh does not report"
[[ "$(nerv_pgrep "stixel ")" == "$bystander" ]] || fail "the stixel stage beside it was restarted too"
if grep -q "restarted stixel" "$tmp/up.log"; then fail "stixel restarted: $(cat "$tmp/up.log")"; fi
pass "$(grep -o "validator/0 (pid $victim) sent no health for [0-9.]* s" "$tmp/up.log"): killed, restarted as pid $fresh, reporting again; stixel untouched"
# Anyone on the bus sees it: the supervisor's report counts the restart and says why.
supervisor() { "$BIN/nerv_up" --status --listen 1.5 2>/dev/null | grep "^nerv_up/$host " || true; }
wait_until 10 bash -c "$(declare -f supervisor); BIN='$BIN' host='$host' supervisor | grep -q 'errors 1 .*last: validator/0 (pid $victim) killed by signal 9 (hung)'" \
  || fail "nerv_up's report does not show the restart: $(supervisor)"
pass "nerv_up's own report: $(supervisor | sed 's/  */ /g')"
# A service that dies of SIGILL (a build for another CPU) is said to, with the build's -march.
ill=$(nerv_pgrep "stixel ")
kill -ILL "$ill"
wait_until 10 grep -q "stixel/0 (pid $ill) killed by signal 4 (illegal instruction: built with -march=" "$tmp/up.log" \
  || fail "SIGILL not named: $(grep "pid $ill" "$tmp/up.log")"
pass "$(grep -o "stixel/0 (pid $ill) killed by signal 4 (illegal instruction: [^)]*)" "$tmp/up.log")"
stop_children
no_survivors || fail "processes survived"
echo "3 passed, 0 failed"

#!/usr/bin/env bash
# nerv_up records the bus (run.record): the real lcm-logger, supervised, writes split
# files named by their UTC start that together hold every frame's messages; a killed
# logger is started again; the oldest recordings beyond keep_mb are deleted and nothing
# else in the folder is; the messages the logger itself drops (a queue for the disk
# that overflows) are counted and said; and on a disk with less than min_free_mb free the logger is
# stopped and started again once space is back, while the services go on detecting.
# The full disk is a 40 MB tmpfs in a mount namespace of this test's own.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT
data=$(synthetic_sequence urban 6)
logger_pattern=$LOGGER_PATTERN

config() {  # config NAME FOLDER SPLIT_MB KEEP_MB MIN_FREE_MB -> $tmp/NAME.yaml
  cp "$NERV_ROOT/config/pipeline.yaml" "$tmp/$1.yaml"
  printf 'run:\n  record:\n    folder: %s\n    split_mb: %s\n    keep_mb: %s\n    min_free_mb: %s\n' "$2" "$3" "$4" "$5" >>"$tmp/$1.yaml"
}
send() {  # send TIMES RATE: the 6 urban frames TIMES through the pipeline; every one must come out
  "$BIN/nerv_source" --data "$data" --repeat "$1" --rate "$2" --lcm-url "$URL" --drain-timeout 30 \
    --wait-for "$(IFS=,; echo "${SERVICES[*]}")" 2>"$tmp/source.log" \
    || fail "not every frame came out: $(tail -c 300 "$tmp/source.log")"
}
events() {  # events CHANNEL FILE...: how many events of CHANNEL the files hold together
  local c=$1 f n=0
  shift
  for f in "$@"; do n=$(( n + $("$BIN/nerv_export" "$f" --json --no-blobs | grep -c "\"channel\":\"$c\"" || true) )); done
  echo "$n"
}
logger() { pgrep -P "$up_pid" -f "$logger_pattern"; }  # the lcm-logger of this test's nerv_up
up() {  # up NAME: nerv_up with $tmp/NAME.yaml, its log $tmp/NAME.log
  start_child "$tmp/$1.log" "$BIN/nerv_up" --config "$tmp/$1.yaml" --lcm-url "$URL" --quiet
  up_pid=${CHILDREN[-1]}
  wait_until 20 logger >/dev/null || fail "$1: no lcm-logger started: $(cat "$tmp/$1.log")"
}

# 1. Every frame recorded, across split files named by their UTC start.
config split "$tmp/rec" 4 0 0
# A source waits for the instances --list names: the logger sends no health, so it is not one.
listed=$("$BIN/nerv_up" --config "$tmp/split.yaml" --list | tr '\n' ' ')
[[ "$listed" == "stereo_matcher/0 stixel/0 snv_extrinsic/0 validator/0 " ]] || fail "nerv_up --list: $listed"
up split
started_s=$(date +%s)
send 2 10
sleep 0.5
stop_children
mapfile -t files < <(ls "$tmp/rec"/nerv-*.lcmlog.* | sort)
(( ${#files[@]} >= 3 )) || fail "12 frames of about 2.35 MB in ${#files[@]} files of 4 MB: ${files[*]}"
first=$(basename "${files[0]}")
[[ "$first" =~ ^nerv-([0-9]{8}-[0-9]{4})[0-9]{2}\.lcmlog\.00$ ]] || fail "first file named $first"
start_s=$(date -u -d "$(echo "${BASH_REMATCH[1]}" | sed -E 's/(....)(..)(..)-(..)(..)/\1-\2-\3 \4:\5/')" +%s)
(( start_s >= started_s - 60 && start_s <= started_s + 60 )) || fail "$first is not named by its UTC start ($(date -u -d @"$started_s"))"
for c in STEREO_FRAME DISPARITY STIXELS SURFACE_NORMALS EXTRINSICS DETECTIONS; do
  n=$(events "$c" "${files[@]}")
  [[ "$n" == 12 ]] || fail "$c: $n of 12 events in the recording"
done
grep -q "lcm-logger is dropping" "$tmp/split.log" && fail "drops said with the logger's default queue: $(grep "lcm-logger" "$tmp/split.log")"
grep -q "recording into $tmp/rec/nerv-.*\.lcmlog\.00" "$tmp/split.log" || fail "the file being written is not said: $(cat "$tmp/split.log")"
pass "12 frames, every channel's 12 events in ${#files[@]} files, the first $first"
# The split recording is one drive to nerv replay: the files in name order, one after another.
"$NERV_ROOT/tools/nerv" replay "$tmp/rec"/nerv-*.lcmlog.* --lcm-url "$URL" --out "$tmp/replayed" >"$tmp/replay.txt" 2>&1 \
  || fail "replay of the split recording: $(tail -n 3 "$tmp/replay.txt")"
grep -q "replayed 12 frames, 12 with DETECTIONS" "$tmp/replay.txt" || fail "replay: $(tail -n 3 "$tmp/replay.txt")"
pass "$(grep -o "replaying .* through" "$tmp/replay.txt" | sed 's/ through//'): $(grep -o "replayed 12 frames, 12 with DETECTIONS" "$tmp/replay.txt")"

# 2. A killed logger is started again and the frames after it are recorded.
config kill "$tmp/rec2" 1024 0 0
up kill
victim=$(logger)
kill -KILL "$victim"
wait_until 20 grep -q "restarted lcm-logger/0" "$tmp/kill.log" || fail "the logger was not restarted: $(cat "$tmp/kill.log")"
grep -q "lcm-logger/0 (pid $victim) killed by signal 9" "$tmp/kill.log" || fail "the logger's death not said: $(cat "$tmp/kill.log")"
sleep 0.5
send 1 10
sleep 0.5
stop_children
n=$(events DETECTIONS "$tmp/rec2"/nerv-*)
[[ "$n" == 6 ]] || fail "after the logger's restart $n of 6 DETECTIONS recorded"
pass "logger $victim killed, restarted, the next 6 frames recorded"

# 3. keep_mb: the oldest recordings go, the newest and other files stay.
mkdir -p "$tmp/rec3"
head -c 3000000 /dev/zero >"$tmp/rec3/drive_monday.lcmlog"
config keep "$tmp/rec3" 2 6 0
up keep
send 2 10
sleep 2.5  # nerv_up's check comes once a second
total=$(ls -l "$tmp/rec3"/nerv-* | awk '{s += $5} END {print s}')
(( total <= 6 * 1048576 )) || fail "the recordings hold $total bytes after the check, over keep_mb 6"
[[ -f "$tmp/rec3/drive_monday.lcmlog" ]] || fail "a file that is not a recording was deleted"
deleted=$(grep -c "deleted the recording" "$tmp/keep.log" || true)
(( deleted > 0 )) || fail "nothing deleted: $(cat "$tmp/keep.log")"
status=$("$BIN/nerv_up" --status --lcm-url "$URL" --listen 1.5 | grep "^nerv_up/" || true)
[[ "$status" =~ recording_mb\ ([0-9.]+) ]] || fail "nerv_up's report has no recording_mb: $status"
stop_children
pass "$deleted files deleted, $total bytes left (keep_mb 6), drive_monday.lcmlog kept; $(echo "$status" | grep -o 'recording_mb [0-9.]*')"

# 4. The logger's own drops: with a queue smaller than one frame (max_unwritten_mb 0.5 against
# 0.93 MB gray frames) lcm-logger drops what waits for the disk, which only its standard
# output says; nerv_up counts it and says it, while the services still get every frame.
config drops "$tmp/rec4" 1024 0 0
printf '    max_unwritten_mb: 0.5\n' >>"$tmp/drops.yaml"
up drops
"$BIN/nerv_source" --data "$data" --rate 10 --encoding gray8 --lcm-url "$URL" --drain-timeout 30 \
  --wait-for "$(IFS=,; echo "${SERVICES[*]}")" 2>"$tmp/source.log" || fail "not every frame came out: $(tail -c 300 "$tmp/source.log")"
wait_until 10 grep -q "lcm-logger is dropping messages: more than run.record.max_unwritten_mb 0.5 waited for the disk of $tmp/rec4" "$tmp/drops.log" || fail "no drop said: $(cat "$tmp/drops.log")"
status=$("$BIN/nerv_up" --status --lcm-url "$URL" --listen 1.5 | grep "^nerv_up/" || true)
[[ "$status" == *"last: lcm-logger is dropping messages"* ]] || fail "nerv_up's report does not carry the drops: $status"
stop_children
recorded=$(events STEREO_FRAME "$tmp/rec4"/nerv-*)
(( recorded < 6 )) || fail "$recorded of 6 frames recorded: nothing was dropped"
grep -q "\"recording_dropped\"" <("$BIN/nerv_export" "$tmp/rec4"/nerv-* --json --no-blobs) \
  || fail "no recording_dropped counter in the recorded NERV_HEALTH"
pass "$recorded of 6 frames recorded with max_unwritten_mb 0.5, said: $(grep -o "at least [0-9]* in all" "$tmp/drops.log" | tail -n 1)"

# 5. A full disk: a 40 MB tmpfs of this test's own mount namespace, min_free_mb 20.
if ! unshare -m true 2>/dev/null; then echo "SKIP: no mount namespace for the full-disk check" >&2; echo "5 passed"; exit 0; fi
cat >"$tmp/full.sh" <<EOF
set -euo pipefail
source "$NERV_ROOT/tests/integration/lib.sh"
$(declare -f config send events up logger)
tmp=$tmp data=$data logger_pattern='$logger_pattern'
trap 'stop_children' EXIT
mkdir -p "$tmp/small"
mount -t tmpfs -o size=40m tmpfs "$tmp/small"
config full "$tmp/small/rec" 4 0 20
up full
head -c 25000000 /dev/zero >"$tmp/small/ballast"   # 15 MB left: below 20
wait_until 10 grep -q "recording paused: 1[0-9] MB free on $tmp/small/rec, below run.record.min_free_mb 20" "$tmp/full.log" \
  || fail "not paused below min_free_mb: \$(cat "$tmp/full.log")"
wait_until 10 eval '! logger >/dev/null' || fail "the logger still runs on a full disk"
send 1 10   # the services go on while nothing is recorded
rm "$tmp/small/ballast"
wait_until 10 grep -q "recording resumed: [0-9]* MB free" "$tmp/full.log" || fail "not resumed: \$(cat "$tmp/full.log")"
wait_until 10 logger >/dev/null || fail "no logger after the resume"
sleep 0.5
send 4 2   # 56 MB at 2 Hz into 40 MB: paused again before the disk is full
free=\$(df -m --output=avail "$tmp/small" | tail -n 1 | tr -d ' ')
(( free >= 8 )) || fail "only \$free MB left on the small disk"
grep -c "recording paused" "$tmp/full.log" | grep -qx 2 || fail "not paused a second time: \$(cat "$tmp/full.log")"
grep -q "restarted lcm-logger" "$tmp/full.log" && fail "a pause counted as a restart: \$(cat "$tmp/full.log")"
stop_children
echo "paused at 15 MB free, resumed, paused again with \$free MB left"
EOF
out=$(NERV_IN_NETNS=1 unshare -m bash "$tmp/full.sh" 2>&1) || fail "full disk: $out"
pass "full disk: $(echo "$out" | tail -n 1)"
no_survivors || fail "processes survived: $(pgrep -af "^$BIN/|lcm-logger")"
echo "6 passed, 0 failed"
